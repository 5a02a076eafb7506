// H.264 movies through FFmpeg's libraries (libavcodec with libx264, libavformat's MP4
// muxer, libswscale): yuv420p with BT.709 colour tags, even dimensions, constant frame
// rate, the index at the front of the file (faststart), so that the file plays in
// presentation software, browsers and phones. Written under a temporary name and renamed
// into place by finish(); destroying an unfinished encoder removes the temporary file.
#pragma once

#include <memory>
#include <string>

#include "image/image.hpp"

namespace bsmpm::render {

struct MovieSettings {
  int width = 1280, height = 720;  // must be even (4:2:0 chroma)
  int fps = 30;
  int crf = 18;                    // x264 constant quality: 18 is visually lossless
  std::string preset = "medium";   // x264 speed/size trade-off
};

class MovieEncoder {
 public:
  // Opens the encoder and the (temporary) output file; throws UsageError for bad settings,
  // IoError when the file cannot be created or libx264 is missing.
  MovieEncoder(const std::string& path, const MovieSettings& settings);
  ~MovieEncoder();
  MovieEncoder(const MovieEncoder&) = delete;
  MovieEncoder& operator=(const MovieEncoder&) = delete;

  // Appends one frame (the size given in the settings), shown for 1/fps s.
  void add_frame(const Image& frame);
  // Flushes the encoder, writes the index and moves the file into place.
  void finish();

 private:
  struct Av;  // the FFmpeg objects
  std::unique_ptr<Av> av_;
  std::string path_;
  MovieSettings settings_;
  long frames_ = 0;
};

}  // namespace bsmpm::render

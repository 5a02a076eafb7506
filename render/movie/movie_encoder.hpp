// H.264 movies through FFmpeg's libraries (libavcodec with libx264, libavformat's MP4
// muxer, libswscale): yuv420p with BT.709 colour tags, even dimensions, constant frame
// rate, the index at the front of the file (faststart), so that the file plays in
// presentation software, browsers and phones. Written under a temporary name and renamed
// into place by finish(); destroying an unfinished encoder removes the temporary file.
// Built into the module bsmpm_movie.so only (movie_writer.hpp).
#pragma once

#include <memory>
#include <string>

#include "movie/movie_writer.hpp"

namespace bsmpm::render {

class MovieEncoder final : public MovieWriter {
 public:
  // Opens the encoder and the (temporary) output file; throws UsageError for bad settings,
  // IoError when the file cannot be created or libx264 is missing.
  MovieEncoder(const std::string& path, const MovieSettings& settings);
  ~MovieEncoder() override;
  MovieEncoder(const MovieEncoder&) = delete;
  MovieEncoder& operator=(const MovieEncoder&) = delete;

  // Appends one frame (the size given in the settings), shown for 1/fps s.
  void add_frame(const Image& frame) override;
  // Flushes the encoder, writes the index and moves the file into place.
  void finish() override;

 private:
  struct Av;  // the FFmpeg objects
  std::unique_ptr<Av> av_;
  std::string path_;
  MovieSettings settings_;
  long frames_ = 0;
};

}  // namespace bsmpm::render

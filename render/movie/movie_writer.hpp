// A movie being written, frame by frame (H.264 in MP4: movie_encoder.hpp). FFmpeg's libraries
// and theirs (libx264, libjxl, Highway, ... about a hundred shared libraries) live in a module,
// bsmpm_movie.so beside the program, that open_movie() loads on first use: every other
// command starts without them (and runs under valgrind on CPUs whose instructions those
// libraries' start-up code uses and valgrind does not decode).
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

class MovieWriter {
 public:
  virtual ~MovieWriter() = default;
  // Appends one frame (the size given in the settings), shown for 1/fps s.
  virtual void add_frame(const Image& frame) = 0;
  // Flushes the encoder, writes the index and moves the file into place.
  virtual void finish() = 0;
};

// Opens the movie at `path` (written under a temporary name until finish(); destroying an
// unfinished writer removes it). Throws UsageError for bad settings, IoError when the file
// cannot be created, libx264 is missing or the module cannot be loaded (naming it).
std::unique_ptr<MovieWriter> open_movie(const std::string& path, const MovieSettings& settings);

// The module's entry point, looked up by open_movie(): a new encoder (the caller owns it).
using OpenMovieFunction = MovieWriter*(const std::string& path, const MovieSettings& settings);
inline constexpr const char* kOpenMovieSymbol = "bsmpm_open_movie";
inline constexpr const char* kMovieModuleName = "bsmpm_movie.so";

}  // namespace bsmpm::render

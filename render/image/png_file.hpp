// PNG files through libpng's simplified API (libpng 1.6): 8-bit RGB out, anything in.
#pragma once

#include <string>

#include "image/image.hpp"

namespace bsmpm::render {

// Writes `image` as an 8-bit RGB PNG; the file appears only once complete (PendingFile).
// Throws IoError naming the path.
void write_png(const Image& image, const std::string& path);

// Reads any PNG (grey, palette, 16-bit, with alpha) as 8-bit RGB; alpha is composited
// over white. Throws IoError naming the path.
Image read_png(const std::string& path);

}  // namespace bsmpm::render

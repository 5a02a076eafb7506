#include "image/png_file.hpp"

#include <png.h>

#include <cstring>
#include <filesystem>

#include "core/error.hpp"
#include "output/pending_file.hpp"

namespace bsmpm::render {

void write_png(const Image& image, const std::string& path) {
  if (image.empty()) throw IoError(path + ": refusing to write an empty image");
  PendingFile out(path);
  png_image info;
  std::memset(&info, 0, sizeof info);
  info.version = PNG_IMAGE_VERSION;
  info.width = static_cast<png_uint_32>(image.width());
  info.height = static_cast<png_uint_32>(image.height());
  info.format = PNG_FORMAT_RGB;
  info.flags = PNG_IMAGE_FLAG_FAST;
  if (!png_image_write_to_file(&info, out.temp_path().c_str(), 0, image.data(),
                               static_cast<png_int_32>(image.row_bytes()), nullptr))
    throw IoError(path + ": cannot write PNG: " + info.message);
  out.commit();
}

Image read_png(const std::string& path) {
  if (!std::filesystem::exists(path)) throw IoError(path + ": no such file");
  png_image info;
  std::memset(&info, 0, sizeof info);
  info.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&info, path.c_str())) throw IoError(path + ": not a readable PNG: " + info.message);
  info.format = PNG_FORMAT_RGB;
  Image image(static_cast<int>(info.width), static_cast<int>(info.height));
  const png_color white{255, 255, 255};
  if (!png_image_finish_read(&info, &white, image.data(), static_cast<png_int_32>(image.row_bytes()), nullptr)) {
    png_image_free(&info);
    throw IoError(path + ": cannot decode PNG: " + info.message);
  }
  return image;
}

}  // namespace bsmpm::render

#include "gl/osmesa_context.hpp"

#include <GL/osmesa.h>

#include <string>

#include "core/error.hpp"

namespace bsmpm::render {

OsMesaContext::OsMesaContext(int width, int height) {
  // A depth buffer for the particle painter (the nearest particle's splat wins a pixel);
  // no stencil or accumulation buffer: layers are drawn in order (painter's algorithm).
  context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!context_) throw Error("OSMesa: cannot create an off-screen OpenGL context (is libosmesa6 installed?)");
  try {
    resize(width, height);
  } catch (...) {
    OSMesaDestroyContext(context_);
    throw;
  }
}

OsMesaContext::~OsMesaContext() { OSMesaDestroyContext(context_); }

void OsMesaContext::resize(int width, int height) {
  GLint max_width = 0, max_height = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_width);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_height);
  if (width < 1 || height < 1 || (max_width > 0 && width > max_width) || (max_height > 0 && height > max_height))
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is outside what OSMesa renders (1.." + std::to_string(max_width) + " x 1.." +
                     std::to_string(max_height) + ")");
  width_ = width;
  height_ = height;
  rgba_.assign(4 * static_cast<std::size_t>(width) * height, 0);
  make_current();
}

void OsMesaContext::make_current() {
  if (!OSMesaMakeCurrent(context_, rgba_.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw Error("OSMesa: cannot bind a " + std::to_string(width_) + "x" + std::to_string(height_) + " buffer");
  OSMesaPixelStore(OSMESA_Y_UP, 0);
}

Image OsMesaContext::read_image() const {
  glFinish();
  Image image(width_, height_);
  const std::size_t n = static_cast<std::size_t>(width_) * height_;
  std::uint8_t* out = image.data();
  for (std::size_t k = 0; k < n; ++k) {
    out[3 * k] = rgba_[4 * k];
    out[3 * k + 1] = rgba_[4 * k + 1];
    out[3 * k + 2] = rgba_[4 * k + 2];
  }
  return image;
}

}  // namespace bsmpm::render

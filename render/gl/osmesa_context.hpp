// An off-screen OpenGL context (Mesa's OSMesa, rasterised by llvmpipe on the CPU): no
// display, no GPU. The context renders into a buffer this class owns; rows are stored top
// to bottom (OSMESA_Y_UP = 0), so the buffer reads out as an Image without flipping.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.hpp"

struct osmesa_context;  // OSMesaContext, without pulling GL headers into every user

namespace bsmpm::render {

class OsMesaContext {
 public:
  // Creates an RGBA context and makes it current on this thread with a width x height
  // buffer. Throws bsmpm::Error when OSMesa cannot create or bind it.
  OsMesaContext(int width, int height);
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  // Rebinds the context to a buffer of a new size (and makes it current).
  void resize(int width, int height);
  // Makes this context current on the calling thread (one thread at a time).
  void make_current();
  // Waits for GL to finish and copies the buffer out as RGB.
  Image read_image() const;

 private:
  osmesa_context* context_ = nullptr;
  std::vector<std::uint8_t> rgba_;
  int width_ = 0, height_ = 0;
};

}  // namespace bsmpm::render

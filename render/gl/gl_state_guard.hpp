// Saves the OpenGL state a painter changes and restores it when the guard goes out of
// scope, also when the painter throws: the viewport, the enabled capabilities, the depth and
// point settings (glPushAttrib), the projection matrix, the current program and the bound
// array buffer. The painter then sets what it needs without writing down what it found.
#pragma once

#include <GL/gl.h>

namespace bsmpm::render {

class GlStateGuard {
 public:
  GlStateGuard();
  ~GlStateGuard();
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  // The viewport found when the guard was made: x, y, width, height.
  const GLint* viewport() const { return viewport_; }

 private:
  GLint viewport_[4] = {0, 0, 0, 0};
  GLint matrix_mode_ = GL_MODELVIEW;
  GLint program_ = 0;
  GLint array_buffer_ = 0;
};

}  // namespace bsmpm::render

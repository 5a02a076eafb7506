#define GL_GLEXT_PROTOTYPES
#include "gl/gl_state_guard.hpp"

#include <GL/glext.h>

namespace bsmpm::render {

GlStateGuard::GlStateGuard() {
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_MATRIX_MODE, &matrix_mode_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
  glPushAttrib(GL_VIEWPORT_BIT | GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_POINT_BIT);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glMatrixMode(static_cast<GLenum>(matrix_mode_));
}

GlStateGuard::~GlStateGuard() {
  glMatrixMode(GL_PROJECTION);
  glPopMatrix();
  glMatrixMode(static_cast<GLenum>(matrix_mode_));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(array_buffer_));
  glUseProgram(static_cast<GLuint>(program_));
  glPopAttrib();
}

}  // namespace bsmpm::render

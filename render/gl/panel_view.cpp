#include "gl/panel_view.hpp"

#include <GL/gl.h>

namespace bsmpm::render {

void set_panel_view(const PixelRect& pixels, const WorldRect& world, int image_height) {
  // GL window coordinates start at the bottom-left; OSMesa (Y_UP = 0) stores rows top-down.
  const int gl_y = image_height - pixels.bottom();
  glViewport(pixels.x, gl_y, pixels.width, pixels.height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(pixels.x, gl_y, pixels.width, pixels.height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(world.min.x(), world.max.x(), world.min.y(), world.max.y(), -1.0, 1.0);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
}

void reset_view(int image_width, int image_height) {
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, image_width, image_height);
}

}  // namespace bsmpm::render

#include "paint/tank_painter.hpp"

#include <GL/gl.h>

namespace bsmpm::render {

void paint_tank_walls(const WorldRect& domain, double t, Rgb color) {
  const double x0 = domain.min.x(), y0 = domain.min.y(), x1 = domain.max.x(), y1 = domain.max.y();
  glColor3ub(color.r, color.g, color.b);
  glRectd(x0 - t, y0 - t, x0, y1 + t);  // left
  glRectd(x1, y0 - t, x1 + t, y1 + t);  // right
  glRectd(x0, y0 - t, x1, y0);          // bottom
  glRectd(x0, y1, x1, y1 + t);          // top
}

}  // namespace bsmpm::render

// Rectangles: in pixels (origin top-left, y down) and in world coordinates (metres, y up).
#pragma once

#include <algorithm>

#include "core/types.hpp"
#include "image/image.hpp"

namespace bsmpm::render {

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
  int right() const { return x + width; }    // one past the last column
  int bottom() const { return y + height; }  // one past the last row
  PixelRect expanded(int by) const { return {x - by, y - by, width + 2 * by, height + 2 * by}; }
};

struct WorldRect {
  Vec2 min = Vec2::Zero(), max = Vec2::Ones();
  double width() const { return max.x() - min.x(); }
  double height() const { return max.y() - min.y(); }
};

inline void fill_rect(Image& image, const PixelRect& r, Rgb color) {
  const int x0 = std::max(r.x, 0), x1 = std::min(r.right(), image.width());
  const int y0 = std::max(r.y, 0), y1 = std::min(r.bottom(), image.height());
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) image.set(x, y, color);
}

}  // namespace bsmpm::render

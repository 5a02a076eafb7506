// Where a world point of a figure's panel lands in the image, for tests that check colours
// at known pixels.
#pragma once

#include <utility>

#include "image/rect.hpp"

namespace bsmpm::test {

// Pixel (column, row) of world point `p` in a panel drawn into `plot` with `view`.
inline std::pair<int, int> pixel_of(const render::PixelRect& plot, const render::WorldRect& view, Vec2 p) {
  const double fx = (p.x() - view.min.x()) / view.width(), fy = (p.y() - view.min.y()) / view.height();
  return {plot.x + static_cast<int>(fx * plot.width), plot.bottom() - 1 - static_cast<int>(fy * plot.height)};
}

// World point at the centre of pixel (column, row) of that panel.
inline Vec2 world_of(const render::PixelRect& plot, const render::WorldRect& view, int column, int row) {
  return Vec2(view.min.x() + (column - plot.x + 0.5) / plot.width * view.width(),
              view.min.y() + (plot.bottom() - row - 0.5) / plot.height * view.height());
}

}  // namespace bsmpm::test

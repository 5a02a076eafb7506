// Where a world point lands in a rendered panel, for tests that check pixels.
#pragma once

#include <utility>

#include "core/types.hpp"
#include "image/rect.hpp"

namespace bsmpm::test {

// Pixel of world point `p` in a panel: the view stretched onto the plot, y up.
inline std::pair<int, int> pixel_of(const render::PixelRect& plot, const render::WorldRect& view, Vec2 p) {
  const double fx = (p.x() - view.min.x()) / view.width(), fy = (p.y() - view.min.y()) / view.height();
  return {plot.x + static_cast<int>(fx * plot.width), plot.bottom() - 1 - static_cast<int>(fy * plot.height)};
}

}  // namespace bsmpm::test

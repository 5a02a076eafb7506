// The tank: the domain's four walls, drawn just outside the domain, so that drawn over
// the particles they hide no particle but trim the splats that overhang a wall.
#pragma once

#include "image/image.hpp"
#include "image/rect.hpp"

namespace bsmpm::render {

// GL; needs set_panel_view. `thickness` is in world units (the caller converts pixels).
void paint_tank_walls(const WorldRect& domain, double thickness, Rgb color);

}  // namespace bsmpm::render

// Where GL draws: a world rectangle mapped onto a pixel rectangle of the current buffer,
// with drawing clipped (scissored) to that rectangle.
#pragma once

#include "image/rect.hpp"

namespace bsmpm::render {

// `pixels` is in image coordinates (origin top-left); `world` is stretched onto it, so the
// caller keeps the aspect ratios equal. Sets viewport, scissor and projection.
void set_panel_view(const PixelRect& pixels, const WorldRect& world, int image_height);

// Back to whole-buffer drawing.
void reset_view(int image_width, int image_height);

}  // namespace bsmpm::render

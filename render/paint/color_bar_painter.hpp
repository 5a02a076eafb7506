// A colour bar with its title, ticks and tick labels, drawn onto the finished image (after
// the GL pass): the gradient's end rows or columns are exactly the colour map's ends.
#pragma once

#include "figure/figure_layout.hpp"
#include "figure/figure_spec.hpp"
#include "image/image.hpp"
#include "text/font.hpp"

namespace bsmpm::render {

inline constexpr Rgb kInkColor{30, 30, 30};

void paint_color_bar(Image& image, Font& font, const ColorBarLayout& layout, const ColorScale& scale, int font_px);

}  // namespace bsmpm::render

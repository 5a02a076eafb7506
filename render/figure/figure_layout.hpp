// Where everything of a figure goes, in pixels: the header line, each panel's plot (the
// world view fitted with its aspect ratio kept), panel labels and colour bars. Colour bars
// go to the right (stacked) or along the bottom (side by side); "auto" takes whichever
// leaves the panels larger, so a wide tank gets bars below and a tall one bars beside.
#pragma once

#include <vector>

#include "figure/figure_spec.hpp"
#include "image/rect.hpp"
#include "text/font.hpp"

namespace bsmpm::render {

struct ColorBarLayout {
  PixelRect bar;          // the gradient itself
  bool vertical = false;  // low values at the bottom (vertical) or left (horizontal)
  int tick_length = 0;
  int tick_target = 5;    // about this many ticks
  int title_x = 0, title_baseline = 0;  // first title line (left end; centre if horizontal)
};

struct FigureLayout {
  int font_px = 0;        // header
  int small_font_px = 0;  // ticks, bar titles, panel labels
  int margin = 0;
  int wall_px = 0;        // tank wall thickness
  PixelRect header;
  std::vector<PixelRect> plots;        // per panel: the view, aspect kept
  std::vector<int> label_baselines;    // per panel: baseline of its label (above the plot)
  std::vector<ColorBarLayout> bars;    // water first, then solids (those the spec has)
  double pixels_per_unit = 0.0;        // of the view, the same in every panel
  ColorBarPlacement placement = ColorBarPlacement::kRight;
};

FigureLayout compute_figure_layout(const FigureSpec& spec, Font& font);

// The smallest height (even) at which the panels of `spec` reach the size its width allows:
// for grid figures whose height should follow their content. `spec.font_px` must be set
// (and kept for rendering); "auto" bar placement becomes the bottom.
int fitted_height(FigureSpec spec, Font& font);

}  // namespace bsmpm::render

// What a figure shows: one or more panels (frames of a run) in a grid, sharing one view,
// one colour scale per particle kind, and one set of colour bars.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "color/color_map.hpp"
#include "figure/frame_particles.hpp"
#include "image/rect.hpp"

namespace bsmpm::render {

enum class ColorBarPlacement { kAuto, kRight, kBottom };

// One colour bar: the map, the values it spans, and how to label them.
struct ColorScale {
  std::string subject;   // "water", "solid"
  std::string quantity;  // "pressure [kPa]"
  ColorMap map;
  ValueRange range;      // SI units
  double display_scale;  // tick label = value * display_scale
};

struct FigurePanel {
  const FrameParticles* particles = nullptr;
  std::string label;  // drawn above the panel ("T* = 2.00"); empty for none
};

struct FigureSpec {
  int width = 1280, height = 720;
  int font_px = 0;  // 0: default_font_px(width, height)
  int rows = 1, cols = 1;
  WorldRect view;    // the world window of every panel
  WorldRect domain;  // the tank; its walls are drawn just outside
  double splat_scale = 1.0;  // margin past the outermost particles / (sqrt(volume) / 2)
  ColorBarPlacement placement = ColorBarPlacement::kAuto;
  std::string header_left, header_right;
  std::vector<FigurePanel> panels;  // row-major, at most rows * cols
  std::optional<ColorScale> water, solids;
};

// Font size for an image: 1/60 of the width of a 16:9 frame (21 px at 1280x720, 32 px at
// 1920x1080), at least 9 px.
int default_font_px(int width, int height);

}  // namespace bsmpm::render

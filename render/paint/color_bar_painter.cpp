#include "paint/color_bar_painter.hpp"

#include <cmath>

#include "text/ticks.hpp"

namespace bsmpm::render {

void paint_color_bar(Image& image, Font& font, const ColorBarLayout& layout, const ColorScale& scale, int font_px) {
  const PixelRect& bar = layout.bar;
  const int length = layout.vertical ? bar.height : bar.width;
  // Pixel k along the bar shows t = k / (length - 1): the first and last pixels are the
  // map's ends, as the particles at the range's ends.
  for (int k = 0; k < length; ++k) {
    const Rgb c = scale.map.at(length > 1 ? static_cast<double>(k) / (length - 1) : 0.0);
    if (layout.vertical) fill_rect(image, {bar.x, bar.bottom() - 1 - k, bar.width, 1}, c);
    else fill_rect(image, {bar.x + k, bar.y, 1, bar.height}, c);
  }
  // A frame just outside the gradient.
  fill_rect(image, {bar.x - 1, bar.y - 1, bar.width + 2, 1}, kInkColor);
  fill_rect(image, {bar.x - 1, bar.bottom(), bar.width + 2, 1}, kInkColor);
  fill_rect(image, {bar.x - 1, bar.y, 1, bar.height}, kInkColor);
  fill_rect(image, {bar.right(), bar.y, 1, bar.height}, kInkColor);

  const double lo = scale.range.min * scale.display_scale, hi = scale.range.max * scale.display_scale;
  // Half the height of a digit: centres a tick label vertically on its tick.
  const int half_digit = static_cast<int>(std::lround(0.36 * font_px));
  for (const Tick& tick : nice_ticks(lo, hi, layout.tick_target)) {
    const int offset = static_cast<int>(std::lround((tick.value - lo) / (hi - lo) * (length - 1)));
    if (layout.vertical) {
      const int y = bar.bottom() - 1 - offset;
      fill_rect(image, {bar.right() + 1, y, layout.tick_length, 1}, kInkColor);
      font.draw(image, bar.right() + layout.tick_length + 3, y + half_digit, tick.label, font_px, kInkColor);
    } else {
      const int x = bar.x + offset;
      fill_rect(image, {x, bar.bottom() + 1, 1, layout.tick_length}, kInkColor);
      font.draw(image, x, bar.bottom() + layout.tick_length + 2 + font.ascent(font_px), tick.label, font_px, kInkColor,
                TextAlign::kCenter);
    }
  }
  if (layout.vertical) {
    const int line = font.ascent(font_px) + font.descent(font_px);
    font.draw(image, layout.title_x, layout.title_baseline, scale.subject, font_px, kInkColor);
    font.draw(image, layout.title_x, layout.title_baseline + line, scale.quantity, font_px, kInkColor);
  } else {
    font.draw(image, layout.title_x, layout.title_baseline, scale.subject + " " + scale.quantity, font_px, kInkColor,
              TextAlign::kCenter);
  }
}

}  // namespace bsmpm::render

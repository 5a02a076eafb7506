#include "figure/figure_layout.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "text/ticks.hpp"

namespace bsmpm::render {

namespace {

// Sizes derived from the font size, so that a figure scales as a whole with the image.
struct Metrics {
  int big = 0, small = 0;            // font sizes, px
  int big_line = 0, small_line = 0;  // line heights
  int margin = 0, gap = 0, wall = 0, bar_thickness = 0, tick = 0;
};

Metrics metrics_for(const FigureSpec& spec, Font& font) {
  Metrics m;
  m.big = spec.font_px > 0 ? spec.font_px : default_font_px(spec.width, spec.height);
  m.small = std::max(8, static_cast<int>(std::lround(0.8 * m.big)));
  m.big_line = font.ascent(m.big) + font.descent(m.big);
  m.small_line = font.ascent(m.small) + font.descent(m.small);
  m.margin = std::max(3, static_cast<int>(std::lround(0.6 * m.big)));
  m.gap = std::max(2, static_cast<int>(std::lround(0.4 * m.big)));
  m.wall = std::max(1, static_cast<int>(std::lround(m.big / 8.0)));
  m.bar_thickness = std::max(6, static_cast<int>(std::lround(0.9 * m.big)));
  m.tick = std::max(2, static_cast<int>(std::lround(0.3 * m.big)));
  return m;
}

std::vector<const ColorScale*> scales_of(const FigureSpec& spec) {
  std::vector<const ColorScale*> out;
  if (spec.water) out.push_back(&*spec.water);
  if (spec.solids) out.push_back(&*spec.solids);
  return out;
}

// Widest tick label the bar may get (the finest step has the most decimals).
int widest_tick_label(Font& font, const ColorScale& s, int px) {
  int w = 0;
  for (const Tick& t : nice_ticks(s.range.min * s.display_scale, s.range.max * s.display_scale, 6))
    w = std::max(w, font.text_width(t.label, px));
  return w;
}

// Scale and sizes of the panels when fitted into `area`.
struct PanelFit {
  double scale = 0.0;       // pixels per world unit
  int plot_w = 0, plot_h = 0;
  int label_h = 0;          // label line above each plot (0 without labels)
  int block_h = 0;          // label + walls + plot
  int used_h = 0;           // all rows of blocks and the gaps between them
};

std::optional<PanelFit> fit_panels(const FigureSpec& spec, const Metrics& m, const PixelRect& area) {
  const int rows = std::max(spec.rows, 1), cols = std::max(spec.cols, 1);
  const int cell_w = (area.width - (cols - 1) * m.gap) / cols;
  const int cell_h = (area.height - (rows - 1) * m.gap) / rows;
  bool labelled = false;
  for (const auto& p : spec.panels) labelled = labelled || !p.label.empty();
  PanelFit fit;
  fit.label_h = labelled ? m.small_line : 0;
  const double avail_w = cell_w - 2 * m.wall, avail_h = cell_h - fit.label_h - 2 * m.wall;
  if (avail_w < 8 || avail_h < 8) return std::nullopt;
  const double s = std::min(avail_w / spec.view.width(), avail_h / spec.view.height());
  fit.plot_w = std::max(1, static_cast<int>(std::floor(spec.view.width() * s)));
  fit.plot_h = std::max(1, static_cast<int>(std::floor(spec.view.height() * s)));
  fit.scale = fit.plot_w / spec.view.width();
  fit.block_h = fit.label_h + 2 * m.wall + fit.plot_h;
  fit.used_h = rows * fit.block_h + (rows - 1) * m.gap;
  return fit;
}

// Places the panels of `fit` in `area` (as wide as the fit allows, at least used_h tall):
// columns spread over the width, rows packed and centred vertically.
void place_panels(const FigureSpec& spec, const Metrics& m, const PanelFit& fit, const PixelRect& area, Font& font,
                  FigureLayout& out) {
  const int cols = std::max(spec.cols, 1);
  const int cell_w = (area.width - (cols - 1) * m.gap) / cols;
  const int top = area.y + (area.height - fit.used_h) / 2;
  out.pixels_per_unit = fit.scale;
  out.plots.clear();
  out.label_baselines.clear();
  for (std::size_t i = 0; i < spec.panels.size() && i < static_cast<std::size_t>(std::max(spec.rows, 1) * cols); ++i) {
    const int r = static_cast<int>(i) / cols, c = static_cast<int>(i) % cols;
    const int block_y = top + r * (fit.block_h + m.gap);
    out.plots.push_back({area.x + c * (cell_w + m.gap) + (cell_w - fit.plot_w) / 2, block_y + fit.label_h + m.wall,
                         fit.plot_w, fit.plot_h});
    out.label_baselines.push_back(block_y + font.ascent(m.small));
  }
}

// Bars stacked in a column at the right of `content`, as tall as the panels when they
// leave room; the panels take the rest of the width.
bool layout_right(const FigureSpec& spec, const Metrics& m, const PixelRect& content, Font& font, FigureLayout& out) {
  const auto scales = scales_of(spec);
  int column = 0;
  for (const ColorScale* s : scales)
    column = std::max({column, font.text_width(s->subject, m.small), font.text_width(s->quantity, m.small),
                       m.bar_thickness + m.tick + 3 + widest_tick_label(font, *s, m.small)});
  PixelRect panels = content;
  if (!scales.empty()) panels.width -= column + 2 * m.gap;
  const auto fit = fit_panels(spec, m, panels);
  if (!fit) return false;
  place_panels(spec, m, *fit, panels, font, out);
  const int n = static_cast<int>(scales.size());
  if (n == 0) return true;
  // Each bar needs its two title lines and room for a few ticks.
  const int wanted = n * (2 * m.small_line + 6 * m.small) + (n - 1) * 2 * m.gap;
  PixelRect column_area{content.right() - column, content.y, column, content.height};
  if (fit->used_h >= wanted) {
    column_area.y = panels.y + (panels.height - fit->used_h) / 2;
    column_area.height = fit->used_h;
  }
  const int slot_h = (column_area.height - (n - 1) * 2 * m.gap) / n;
  for (int i = 0; i < n; ++i) {
    const int slot_y = column_area.y + i * (slot_h + 2 * m.gap);
    ColorBarLayout bar;
    bar.vertical = true;
    bar.tick_length = m.tick;
    const int top = slot_y + 2 * m.small_line + m.small / 2;
    const int bottom = slot_y + slot_h - m.small / 2;
    bar.bar = {column_area.x, top, m.bar_thickness, bottom - top};
    if (bar.bar.height < 8) return false;
    bar.tick_target = std::clamp(static_cast<int>(bar.bar.height / (2.5 * m.small)), 2, 6);
    bar.title_x = column_area.x;
    bar.title_baseline = slot_y + font.ascent(m.small);
    out.bars.push_back(bar);
  }
  return true;
}

// Bars side by side in a band right under the panels; panels and band centred vertically.
bool layout_bottom(const FigureSpec& spec, const Metrics& m, const PixelRect& content, Font& font, FigureLayout& out) {
  const auto scales = scales_of(spec);
  const int n = static_cast<int>(scales.size());
  const int band_h = n == 0 ? 0 : 2 * m.gap + m.small_line + m.bar_thickness + m.tick + 2 + m.small_line;
  PixelRect panels = content;
  panels.height -= band_h;
  const auto fit = fit_panels(spec, m, panels);
  if (!fit) return false;
  panels.y += (panels.height - fit->used_h) / 2;
  panels.height = fit->used_h;
  place_panels(spec, m, *fit, panels, font, out);
  if (n == 0) return true;
  const int band_y = panels.bottom() + 2 * m.gap;
  const int slot_w = (content.width - (n - 1) * 3 * m.gap) / n;
  for (int i = 0; i < n; ++i) {
    const int slot_x = content.x + i * (slot_w + 3 * m.gap);
    const int overhang = widest_tick_label(font, *scales[i], m.small) / 2 + 2;
    const int length = std::min(slot_w - 2 * overhang, static_cast<int>(0.45 * content.width));
    if (length < 8) return false;
    ColorBarLayout bar;
    bar.vertical = false;
    bar.tick_length = m.tick;
    bar.bar = {slot_x + (slot_w - length) / 2, band_y + m.small_line, length, m.bar_thickness};
    bar.tick_target = std::clamp(static_cast<int>(length / (5.0 * m.small)), 2, 6);
    bar.title_x = bar.bar.x + length / 2;
    bar.title_baseline = band_y + font.ascent(m.small);
    out.bars.push_back(bar);
  }
  return true;
}

std::optional<FigureLayout> try_layout(const FigureSpec& spec, Font& font, ColorBarPlacement placement) {
  const Metrics m = metrics_for(spec, font);
  FigureLayout out;
  out.font_px = m.big;
  out.small_font_px = m.small;
  out.margin = m.margin;
  out.wall_px = m.wall;
  out.placement = placement;
  const bool header = !spec.header_left.empty() || !spec.header_right.empty();
  out.header = {m.margin, m.margin, spec.width - 2 * m.margin, header ? m.big_line : 0};
  const int top = header ? out.header.bottom() + m.gap : m.margin;
  const PixelRect content{m.margin, top, spec.width - 2 * m.margin, spec.height - top - m.margin};
  const bool ok = placement == ColorBarPlacement::kRight ? layout_right(spec, m, content, font, out)
                                                          : layout_bottom(spec, m, content, font, out);
  if (!ok) return std::nullopt;
  return out;
}

}  // namespace

int default_font_px(int width, int height) {
  return std::max(9, static_cast<int>(std::lround(std::min(width / 60.0, height * 16.0 / 9.0 / 60.0))));
}

FigureLayout compute_figure_layout(const FigureSpec& spec, Font& font) {
  if (!(spec.view.width() > 0 && spec.view.height() > 0)) throw UsageError("the view window has no area");
  std::optional<FigureLayout> layout;
  if (spec.placement != ColorBarPlacement::kAuto) {
    layout = try_layout(spec, font, spec.placement);
  } else {
    // The placement that leaves the panels larger; the bottom on a tie (wide tanks).
    auto right = try_layout(spec, font, ColorBarPlacement::kRight);
    auto bottom = try_layout(spec, font, ColorBarPlacement::kBottom);
    layout = (right && (!bottom || right->pixels_per_unit > bottom->pixels_per_unit)) ? right : bottom;
  }
  if (!layout)
    throw UsageError("a " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " image is too small for " +
                     std::to_string(spec.rows) + "x" + std::to_string(spec.cols) + " panels and their colour bars");
  return *layout;
}

int fitted_height(FigureSpec spec, Font& font) {
  // A font size that followed the height would make the search chase its own tail.
  if (spec.font_px <= 0) throw std::invalid_argument("fitted_height needs an explicit font size");
  if (spec.placement == ColorBarPlacement::kAuto) spec.placement = ColorBarPlacement::kBottom;
  auto scale_at = [&](int height) {
    spec.height = height;
    const auto layout = try_layout(spec, font, spec.placement);
    return layout ? layout->pixels_per_unit : 0.0;
  };
  constexpr int kTallest = 16384;
  const double widest = scale_at(kTallest);
  int lo = 16, hi = kTallest;  // scale_at(hi) reaches the width-limited scale
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (scale_at(mid) >= widest) hi = mid;
    else lo = mid + 1;
  }
  return hi + (hi % 2);
}

}  // namespace bsmpm::render

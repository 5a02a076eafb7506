// The renderer on a frame whose particles the test places: colours at known pixels are
// the colour map's ends, the colour bars span the map exactly, labels are drawn, and the
// image has the size asked for.
#include <catch2/catch.hpp>

#include "compose/figure_renderer.hpp"
#include "paint/color_bar_painter.hpp"
#include "test_support.hpp"
#include "unit/render/figure_pixels.hpp"
#include "unit/render/synthetic_run.hpp"

using namespace bsmpm;
using namespace bsmpm::render;
using bsmpm::test::pixel_of;

namespace {

constexpr Rgb kWhite{255, 255, 255};
// A pressure inside the range [1000, 5000] Pa that falls on entry 128 of the viridis table.
constexpr double kMidPressure = 1000.0 + 4000.0 * 128.0 / 255.0;

// A 1 x 0.5 m tank: a water block at the range's low end on the left, one at its high end
// in the middle, one at mid-range right of it, and a solid block displaced by the solid
// range's maximum on the right.
FrameParticles two_blocks_and_a_solid() {
  FrameParticles f;
  const double h = 0.01;
  auto add = [&](ParticleLayer& layer, Vec2 lo, Vec2 hi, double value) {
    for (const Vec2& p : test::lattice(lo, hi, h)) {
      layer.position.push_back(p);
      layer.side.push_back(h);
      layer.value.push_back(value);
    }
  };
  add(f.water, {0.0, 0.0}, {0.3, 0.3}, 1000.0);  // = water range min
  add(f.water, {0.4, 0.0}, {0.6, 0.3}, 5000.0);  // = water range max
  add(f.water, {0.62, 0.0}, {0.74, 0.2}, kMidPressure);
  add(f.solids, {0.8, 0.0}, {0.9, 0.2}, 0.02);   // = solid range max
  return f;
}

FigureSpec spec_for(const FrameParticles& frame, ColorBarPlacement placement) {
  FigureSpec spec;
  spec.width = 640;
  spec.height = 360;
  spec.view = spec.domain = WorldRect{Vec2(0.0, 0.0), Vec2(1.0, 0.5)};
  spec.placement = placement;
  spec.header_left = "t = 0.30 s   T* = 1.72";
  spec.panels = {FigurePanel{&frame, ""}};
  spec.water = ColorScale{"water", "pressure [kPa]", ColorMap::named("viridis"), {1000.0, 5000.0}, 1e-3};
  spec.solids = ColorScale{"solid", "displacement [mm]", ColorMap::named("jet"), {0.0, 0.02}, 1e3};
  return spec;
}

long ink_pixels(const Image& image, const PixelRect& r) {
  long n = 0;
  for (int y = std::max(r.y, 0); y < std::min(r.bottom(), image.height()); ++y)
    for (int x = std::max(r.x, 0); x < std::min(r.right(), image.width()); ++x) n += !(image.at(x, y) == kWhite);
  return n;
}

}  // namespace

TEST_CASE("A synthetic frame renders with the colour map's ends at known pixels", "[render][figure]") {
  const FrameParticles frame = two_blocks_and_a_solid();
  FigureRenderer renderer;
  for (const auto placement : {ColorBarPlacement::kBottom, ColorBarPlacement::kRight}) {
    const FigureSpec spec = spec_for(frame, placement);
    FigureLayout layout;
    const Image image = renderer.render(spec, &layout);
    INFO("placement " << (placement == ColorBarPlacement::kBottom ? "bottom" : "right"));
    REQUIRE(image.width() == 640);
    REQUIRE(image.height() == 360);
    REQUIRE(layout.plots.size() == 1);
    REQUIRE(layout.bars.size() == 2);
    const PixelRect& plot = layout.plots[0];

    const ColorMap viridis = ColorMap::named("viridis"), jet = ColorMap::named("jet");
    auto at = [&](double x, double y) {
      const auto [px, py] = test::pixel_of(plot, spec.view, Vec2(x, y));
      return image.at(px, py);
    };
    CHECK(at(0.15, 0.15) == viridis.at(0.0));  // low water block
    CHECK(at(0.5, 0.15) == viridis.at(1.0));   // high water block
    CHECK(at(0.85, 0.1) == jet.at(1.0));       // solid at the largest displacement
    CHECK(at(0.68, 0.1) == Rgb{0x21, 0x91, 0x8c});  // mid-range: matplotlib's viridis(0.5)
    CHECK(at(0.7, 0.4) == kWhite);             // empty tank
    // The tank wall just left of the plot.
    CHECK(image.at(plot.x - 1, plot.y + plot.height / 2) == Rgb{70, 70, 70});

    // Colour bars: the gradient's ends are the maps' ends.
    for (std::size_t b = 0; b < 2; ++b) {
      const ColorBarLayout& bar = layout.bars[b];
      const ColorMap& map = b == 0 ? viridis : jet;
      const PixelRect& r = bar.bar;
      if (bar.vertical) {
        CHECK(image.at(r.x + r.width / 2, r.bottom() - 1) == map.at(0.0));
        CHECK(image.at(r.x + r.width / 2, r.y) == map.at(1.0));
      } else {
        CHECK(image.at(r.x, r.y + r.height / 2) == map.at(0.0));
        CHECK(image.at(r.right() - 1, r.y + r.height / 2) == map.at(1.0));
      }
      // Tick labels beside or below the bar, and the title above it.
      const PixelRect labels = bar.vertical ? PixelRect{r.right() + 2, r.y - layout.small_font_px, 60, r.height + 2 * layout.small_font_px}
                                            : PixelRect{r.x - 20, r.bottom() + 2, r.width + 40, 2 * layout.small_font_px};
      CHECK(ink_pixels(image, labels) > 20);
      CHECK(ink_pixels(image, {r.x - 10, bar.title_baseline - layout.small_font_px, r.width + 20, layout.small_font_px}) > 20);
    }
    // The header text.
    CHECK(ink_pixels(image, layout.header) > 50);
  }
}

TEST_CASE("Values outside the colour range take the end colours and missing values are grey", "[render][figure]") {
  FrameParticles frame;
  const double h = 0.01;
  for (const Vec2& p : test::lattice({0.0, 0.0}, {0.2, 0.2}, h)) {
    frame.water.position.push_back(p);
    frame.water.side.push_back(h);
    frame.water.value.push_back(p.x() < 0.1 ? -1e9 : std::nan(""));
  }
  FigureSpec spec = spec_for(frame, ColorBarPlacement::kBottom);
  spec.solids.reset();
  FigureLayout layout;
  FigureRenderer renderer;
  const Image image = renderer.render(spec, &layout);
  CHECK(layout.bars.size() == 1);
  const auto [x_low, y] = test::pixel_of(layout.plots[0], spec.view, Vec2(0.05, 0.1));
  const auto [x_nan, y2] = test::pixel_of(layout.plots[0], spec.view, Vec2(0.15, 0.1));
  CHECK(image.at(x_low, y) == ColorMap::named("viridis").at(0.0));
  CHECK(image.at(x_nan, y2) == ColorMap::kMissingValue);
}

TEST_CASE("A lone particle's splat is sized from its volume", "[render][figure]") {
  // One particle of side 0.1 m in a 1 m wide view of 400 px: with splat scale 1.5 its
  // splat reaches 1.5 * 0.1 m / 2 to either side (no neighbour extends it), a row of
  // 0.15 m * 400 px/m = 60 px through its centre.
  FrameParticles frame;
  frame.water.position = {Vec2(0.5, 0.25)};
  frame.water.side = {0.1};
  frame.water.value = {5000.0};
  FigureSpec spec = spec_for(frame, ColorBarPlacement::kBottom);
  spec.solids.reset();
  spec.splat_scale = 1.5;
  FigureLayout layout;
  FigureRenderer renderer;
  const Image image = renderer.render(spec, &layout);
  const PixelRect& plot = layout.plots[0];
  const int row = plot.y + plot.height / 2;
  int covered = 0;
  for (int x = plot.x; x < plot.right(); ++x) covered += image.at(x, row) == ColorMap::named("viridis").at(1.0);
  // The pixels whose centres lie within 30 px of the particle: 60, or 61 when two centres
  // fall exactly on the splat's edges.
  const double expected = 1.5 * 0.1 * layout.pixels_per_unit;
  CHECK(expected > 50);
  CHECK(covered >= std::floor(expected));
  CHECK(covered <= std::floor(expected) + 1);
}

TEST_CASE("Automatic colour-bar placement leaves the panels larger", "[render][figure]") {
  // A wide tank in a 16:9 frame gets its bars below; a tall one beside it.
  const FrameParticles frame = two_blocks_and_a_solid();
  Font font;
  FigureSpec wide = spec_for(frame, ColorBarPlacement::kAuto);
  wide.view = wide.domain = WorldRect{Vec2(0.0, 0.0), Vec2(1.61, 0.6)};
  const FigureLayout wide_layout = compute_figure_layout(wide, font);
  CHECK(wide_layout.placement == ColorBarPlacement::kBottom);
  for (const auto placement : {ColorBarPlacement::kRight, ColorBarPlacement::kBottom}) {
    wide.placement = placement;
    CHECK(compute_figure_layout(wide, font).pixels_per_unit <= wide_layout.pixels_per_unit);
  }
  FigureSpec tall = spec_for(frame, ColorBarPlacement::kAuto);
  tall.view = tall.domain = WorldRect{Vec2(0.0, 0.0), Vec2(0.2, 0.3)};
  const FigureLayout tall_layout = compute_figure_layout(tall, font);
  CHECK(tall_layout.placement == ColorBarPlacement::kRight);
  REQUIRE(tall_layout.bars.size() == 2);
  CHECK(tall_layout.bars[0].vertical);
  // Bars and panels stay inside the image and do not overlap.
  for (const auto& bar : tall_layout.bars) {
    CHECK(bar.bar.x >= tall_layout.plots[0].right());
    CHECK(bar.bar.bottom() <= tall.height);
  }
}

// Splats drawn from placed particles, checked at known pixels: a sheet whose rows the flow
// has pulled apart is drawn without gaps; a block ends half a spacing beyond its outermost
// particles, to within a pixel; each pixel takes the colour of the nearest particle; the
// water reaches the tank walls and a solid it lies a little way off.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "compose/figure_renderer.hpp"
#include "unit/render/figure_pixels.hpp"

using namespace bsmpm;
using namespace bsmpm::render;
using bsmpm::test::pixel_of;
using bsmpm::test::world_of;

namespace {

constexpr Rgb kWhite{255, 255, 255};
constexpr double kSpacing = 0.02;  // m: 13 to 14 pixels in the figures below

// A 1 x 0.5 m tank drawn 800 px wide, water only (or with solids), splat scale 1.
FigureSpec spec_for(const FrameParticles& frame) {
  FigureSpec spec;
  spec.width = 800;
  spec.height = 450;
  spec.view = spec.domain = WorldRect{Vec2(0.0, 0.0), Vec2(1.0, 0.5)};
  spec.splat_scale = 1.0;
  spec.placement = ColorBarPlacement::kBottom;
  spec.panels = {FigurePanel{&frame, ""}};
  spec.water = ColorScale{"water", "pressure [kPa]", ColorMap::named("viridis"), {0.0, 1.0}, 1e-3};
  if (!frame.solids.empty())
    spec.solids = ColorScale{"solid", "displacement [mm]", ColorMap::named("inferno"), {0.0, 1.0}, 1e3};
  return spec;
}

void add(ParticleLayer& layer, Vec2 p, double value) {
  layer.position.push_back(p);
  layer.side.push_back(kSpacing);  // the volume of intact material, whatever the spacing now
  layer.value.push_back(value);
}

// A block of nx x ny particles at cell centres, its edges at lo and lo + (nx, ny) h.
void add_block(ParticleLayer& layer, Vec2 lo, int nx, int ny, double value) {
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) add(layer, lo + kSpacing * Vec2(i + 0.5, j + 0.5), value);
}

struct Rendered {
  Image image;
  FigureLayout layout;
  FigureSpec spec;

  Rgb at(Vec2 p) const {
    const auto [x, y] = pixel_of(layout.plots[0], spec.view, p);
    return image.at(x, y);
  }
  // Counts the pixels of the panel whose centres lie in the world box [lo, hi] and
  // satisfy `test`.
  long count(Vec2 lo, Vec2 hi, const std::function<bool(Rgb)>& test) const {
    const PixelRect& plot = layout.plots[0];
    long n = 0;
    for (int y = plot.y; y < plot.bottom(); ++y)
      for (int x = plot.x; x < plot.right(); ++x) {
        const Vec2 w = world_of(plot, spec.view, x, y);
        if (w.x() >= lo.x() && w.x() <= hi.x() && w.y() >= lo.y() && w.y() <= hi.y()) n += test(image.at(x, y));
      }
    return n;
  }
  double pixel() const { return 1.0 / layout.pixels_per_unit; }  // m
};

Rendered draw(const FrameParticles& frame) {
  Rendered r;
  r.spec = spec_for(frame);
  FigureRenderer renderer;
  r.image = renderer.render(r.spec, &r.layout);
  REQUIRE(r.layout.plots.size() == 1);
  REQUIRE(r.layout.pixels_per_unit * kSpacing > 12.0);
  return r;
}

bool is_white(Rgb c) { return c == kWhite; }

}  // namespace

TEST_CASE("A sheet whose rows are pulled apart is drawn without gaps", "[render][splat]") {
  // Rows of particles one spacing apart along x, pulled apart across to 2, 2.5 and 3
  // spacings, as in a stretched jet: splats sized from the volume alone leave white lines
  // between the rows.
  for (const double apart : {2.0, 2.5, 3.0}) {
    INFO("rows " << apart << " spacings apart");
    FrameParticles frame;
    const int rows = 6, columns = 25;
    const Vec2 first(0.2, 0.1);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c) add(frame.water, first + kSpacing * Vec2(c, apart * r), 0.5);
    const Rendered out = draw(frame);
    const Vec2 last = first + kSpacing * Vec2(columns - 1, apart * (rows - 1));
    // Nothing white between the first and the last particle of the first and the last row.
    CHECK(out.count(first, last, is_white) == 0);
    CHECK(out.count(first, last, [](Rgb) { return true; }) > 5000);
    // Beyond the outer rows and the rows' ends the sheet ends half a spacing out: the pixel
    // one pixel further is white, the one a pixel short of it water.
    const double edge = 0.5 * kSpacing, px = out.pixel();
    for (int c = 2; c < columns - 2; c += 5) {
      const double x = first.x() + c * kSpacing + 0.5 * kSpacing;  // between two particles
      CHECK(is_white(out.at(Vec2(x, last.y() + edge + px))));
      CHECK(!is_white(out.at(Vec2(x, last.y() + edge - px))));
      CHECK(is_white(out.at(Vec2(x, first.y() - edge - px))));
      CHECK(!is_white(out.at(Vec2(x, first.y() - edge + px))));
    }
    const double y = first.y() + kSpacing * apart * 2.5;  // between two rows
    CHECK(is_white(out.at(Vec2(last.x() + edge + px, y))));
    CHECK(is_white(out.at(Vec2(first.x() - edge - px, y))));
  }
}

TEST_CASE("A block does not bleed past its free surface", "[render][splat]") {
  // 20 x 10 particles at cell centres: the block's edges lie half a spacing beyond its
  // outermost particles, where the splats must end, to within a pixel.
  FrameParticles frame;
  const Vec2 lo(0.3, 0.15);
  const int nx = 20, ny = 10;
  add_block(frame.water, lo, nx, ny, 0.5);
  const Vec2 hi = lo + kSpacing * Vec2(nx, ny);
  const Rendered out = draw(frame);
  const double px = out.pixel();
  for (int k = 1; k < 10; ++k) {
    const double x = lo.x() + k * 0.1 * (hi.x() - lo.x()), y = lo.y() + k * 0.1 * (hi.y() - lo.y());
    INFO("at " << k << "/10 along the edges");
    CHECK(is_white(out.at(Vec2(x, hi.y() + px))));  // top
    CHECK(!is_white(out.at(Vec2(x, hi.y() - px))));
    CHECK(is_white(out.at(Vec2(x, lo.y() - px))));  // bottom
    CHECK(!is_white(out.at(Vec2(x, lo.y() + px))));
    CHECK(is_white(out.at(Vec2(hi.x() + px, y))));  // right
    CHECK(!is_white(out.at(Vec2(hi.x() - px, y))));
    CHECK(is_white(out.at(Vec2(lo.x() - px, y))));  // left
    CHECK(!is_white(out.at(Vec2(lo.x() + px, y))));
  }
  // Corners are cut at 45 degrees (by 0.3 spacing), not grown; the block is whole inside.
  CHECK(is_white(out.at(hi + Vec2(px, px))));
  CHECK(is_white(out.at(lo - Vec2(px, px))));
  const Vec2 corner_cut = Vec2(1.0, 1.0) * 0.3 * kSpacing;
  CHECK(out.count(Vec2(lo.x() + px, lo.y()) + corner_cut, Vec2(hi.x() - px, hi.y()) - corner_cut, is_white) == 0);
  CHECK(out.count(Vec2(lo.x(), lo.y() + px) + corner_cut, Vec2(hi.x(), hi.y() - px) - corner_cut, is_white) == 0);
  // Nothing anywhere beyond the edges plus a pixel.
  const auto outside = [&](Vec2 a, Vec2 b) { return out.count(a, b, [](Rgb c) { return !is_white(c); }); };
  CHECK(outside(Vec2(0.0, hi.y() + px), Vec2(1.0, 0.5)) == 0);
  CHECK(outside(Vec2(0.0, 0.0), Vec2(1.0, lo.y() - px)) == 0);
  CHECK(outside(Vec2(hi.x() + px, 0.0), Vec2(1.0, 0.5)) == 0);
  CHECK(outside(Vec2(0.0, 0.0), Vec2(lo.x() - px, 0.5)) == 0);
}

TEST_CASE("Each pixel takes the colour of the nearest particle", "[render][splat]") {
  // Two blocks side by side with the map's two ends: the boundary between the colours lies
  // midway between the particles on either side, whichever block is drawn last.
  for (const bool low_first : {true, false}) {
    FrameParticles frame;
    const Vec2 lo(0.3, 0.15);
    if (low_first) add_block(frame.water, lo, 10, 10, 0.0);
    add_block(frame.water, lo + Vec2(10 * kSpacing, 0.0), 10, 10, 1.0);
    if (!low_first) add_block(frame.water, lo, 10, 10, 0.0);
    const Rendered out = draw(frame);
    const ColorMap viridis = ColorMap::named("viridis");
    const double x = lo.x() + 10 * kSpacing, px = out.pixel();
    for (int j = 0; j < 10; ++j) {
      const double y = lo.y() + (j + 0.5) * kSpacing;
      CHECK(out.at(Vec2(x - px, y)) == viridis.at(0.0));
      CHECK(out.at(Vec2(x + px, y)) == viridis.at(1.0));
    }
  }
}

TEST_CASE("Water is drawn up to a wall and a solid it lies a little way off", "[render][splat]") {
  // MPM holds particles about a grid cell (two spacings) off a wall and off another body
  // at a contact: a block of water whose edges lie a spacing from the left wall and the
  // floor, and 1.5 spacings from a solid to its right. The gaps are water colour; the
  // water does not reach past the solid.
  FrameParticles frame;
  const Vec2 lo = Vec2(1.0, 1.0) * kSpacing;
  add_block(frame.water, lo, 10, 10, 0.0);
  const double solid_x = lo.x() + 11.5 * kSpacing;
  add_block(frame.solids, Vec2(solid_x, 0.0), 3, 6, 0.0);
  const Rendered out = draw(frame);
  const Rgb water = ColorMap::named("viridis").at(0.0), solid = ColorMap::named("inferno").at(0.0);
  const double px = out.pixel();
  for (int j = 0; j < 10; ++j) {
    const double y = lo.y() + (j + 0.5) * kSpacing;
    CHECK(out.at(Vec2(0.5 * px, y)) == water);     // against the left wall
    CHECK(out.at(Vec2(lo.x() + px, y)) == water);  // the block's own edge
    if (j < 5) CHECK(out.at(Vec2(solid_x - px, y)) == water);  // against the solid
    if (j < 5) CHECK(out.at(Vec2(solid_x + px, y)) == solid);
  }
  for (int i = 0; i < 10; ++i) CHECK(out.at(Vec2(lo.x() + (i + 0.5) * kSpacing, 0.5 * px)) == water);  // the floor
  // Above the solid, beyond the water's own top, nothing is drawn.
  CHECK(is_white(out.at(Vec2(solid_x + 1.5 * kSpacing, 6 * kSpacing + 2 * px))));
  CHECK(is_white(out.at(Vec2(lo.x() + 5 * kSpacing, lo.y() + 10 * kSpacing + px))));
}

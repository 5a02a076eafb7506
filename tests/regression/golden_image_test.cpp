// Golden images (tests/regression/golden_images.hpp): the program's renderings of small
// synthetic runs compared with tests/regression/golden/*.png, and exact colours at known
// world points of the rendered images.
//
// Tolerance. On one machine the output is bit-identical (same Mesa, FreeType and binary),
// whatever the thread count: llvmpipe with LP_NUM_THREADS = 1, 2 and 4, and with 128-bit
// vectors (LP_NATIVE_VECTOR_WIDTH=128, as on a CPU without AVX), gave identical images.
// What may differ on another machine is the rasteriser (another Mesa version). Standing in
// for one, Mesa's other software rasteriser (GALLIUM_DRIVER=softpipe) differs from llvmpipe
// on these images by at most rms 4.3, 1.0 % of the pixels and SSIM 0.995: single pixels at
// the edges of splats, where the two break ties between equally near particles or round a
// splat's edge through a pixel centre differently. Hence rms <= 8, share <= 3 %,
// SSIM >= 0.985 (max is not limited: an edge pixel can go from white to a full colour).
// Real changes exceed it: splat scale 1 -> 1.6 gives rms 10.1, the next frame 29, another
// colour map 29, another colour range 32, the colour bars moved 75 (scale 1 -> 1.3, half a
// pixel more margin at this size, passes: rms 5.5). (Labels: a changed digit would pass;
// their text is tested in unit tests.)
// The exact-pixel checks need no tolerance: they look at particle centres, where only
// splats of the same value or of the next row's reach, and at empty water.
//
// Failures: the rendered image, its difference image and the program's output are kept in
// BSMPM_GOLDEN_FAILURE_DIR (build/tests/golden_failures/) for inspection.
// To regenerate after an intended change: scripts/regenerate_golden_images (the
// update_golden_images build target); this test never writes the golden images.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "figure/figure_layout.hpp"
#include "compose/figure_renderer.hpp"
#include "compose/run_figures.hpp"
#include "image/png_file.hpp"
#include "regression/golden_images.hpp"
#include "test_support.hpp"
#include "unit/render/figure_pixels.hpp"

using namespace bsmpm;
using namespace bsmpm::render;
namespace fs = std::filesystem;

namespace {

const char* kTolerance = "rms=8,share=0.03,ssim=0.985";

// Copies what a failed comparison produced to the failure directory, which outlives the
// test's scratch space; returns where the rendered image went.
fs::path keep_failure(const std::string& name, const std::vector<fs::path>& files) {
  const fs::path keep = BSMPM_GOLDEN_FAILURE_DIR;
  fs::create_directories(keep);
  for (const fs::path& f : files)
    if (fs::exists(f)) fs::copy_file(f, keep / f.filename(), fs::copy_options::overwrite_existing);
  return keep / (name + ".png");
}

// The water particle of `frame` nearest `point`.
std::size_t nearest(const ParticleLayer& layer, Vec2 point) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < layer.size(); ++k)
    if ((layer.position[k] - point).norm() < (layer.position[best] - point).norm()) best = k;
  return best;
}

}  // namespace

TEST_CASE("Rendered frames match the golden images", "[render][golden]") {
  const fs::path dir = test::scratch_dir("golden");
  for (const test::Golden& g : test::goldens()) {
    INFO("golden image " << g.name);
    const test::RenderedGolden r = test::render_golden(g, dir);
    INFO(test::read_text(r.log));
    REQUIRE(r.status == 0);
    const fs::path golden = fs::path(BSMPM_GOLDEN_DIR) / (g.name + ".png");
    REQUIRE(fs::exists(golden));
    const fs::path diff = dir / (g.name + ".diff.png");
    const fs::path log = dir / (g.name + ".compare.log");
    const int status = test::run_program("compare " + golden.string() + " " + r.image.string() + " --tolerance " +
                                             kTolerance + " --diff " + diff.string(),
                                         log)
                           .status;
    if (status == 0) {
      for (const fs::path& f : {r.image, diff, log}) fs::remove(fs::path(BSMPM_GOLDEN_FAILURE_DIR) / f.filename());
    } else {
      const fs::path kept = keep_failure(g.name, {r.image, diff, log});
      INFO(test::read_text(log) << "rendered: " << kept.string()
                                << "\ndifference: " << (kept.parent_path() / diff.filename()).string());
      CHECK(status == 0);
    }
  }
}

TEST_CASE("Golden renderings have the exact colours of known particles and of empty water", "[render][golden]") {
  // The two single-frame goldens, rendered by the program; the layout and the colour scales
  // are recomputed in process from the same run and options. The water particles lie in
  // rows 5 mm apart, and pressure and velocity depend on the height only: the pixel at a
  // particle's centre must show exactly the colour of its own row's value, or of the row
  // just above or below (whose splats, rounded up to whole pixels, may reach it). A wrong
  // colour map, range, field or position gives another colour.
  struct Case {
    std::string golden;
    int frame;
    RenderOptions options;
  };
  RenderOptions pressure;
  pressure.width = 320;
  pressure.height = 180;
  RenderOptions velocity = pressure;
  velocity.field = "velocity";
  velocity.colormap = "jet";
  velocity.colorbar = ColorBarPlacement::kRight;
  const std::vector<Case> cases = {{"dam_break_pressure", 2, pressure}, {"gate_velocity_jet", 3, velocity}};
  const fs::path dir = test::scratch_dir("golden_pixels");
  FigureRenderer renderer;
  for (const Case& c : cases) {
    INFO("golden image " << c.golden);
    const test::Golden* golden = nullptr;
    for (const auto& g : test::goldens())
      if (g.name == c.golden) golden = &g;
    REQUIRE(golden != nullptr);
    REQUIRE(golden->options.find("--frames " + std::to_string(c.frame)) != std::string::npos);
    const test::RenderedGolden r = test::render_golden(*golden, dir);
    REQUIRE(r.status == 0);
    const Image image = read_png(r.image.string());

    const RunReader run(r.run_file);
    const RunFigures figures(run, c.options);
    const FrameParticles frame = figures.load(c.frame);
    const FigureSpec spec = figures.single(frame);
    REQUIRE(spec.width == image.width());
    REQUIRE(spec.height == image.height());
    const FigureLayout layout = compute_figure_layout(spec, renderer.font());
    REQUIRE(layout.plots.size() == 1);
    REQUIRE(spec.water.has_value());
    auto colour_of = [&](double value) { return spec.water->map.at(spec.water->range.normalized(value)); };
    // Water near the column's foot, middle and top (the column is 0.15 x 0.2 m, sheared
    // towards +x).
    const double row = 0.005;
    for (const Vec2& point : {Vec2(0.05, 0.03), Vec2(0.12, 0.1), Vec2(0.05, 0.17)}) {
      const std::size_t k = nearest(frame.water, point);
      const Vec2 x = frame.water.position[k];
      std::vector<Rgb> allowed{colour_of(frame.water.value[k])};
      for (std::size_t q = 0; q < frame.water.size(); ++q)
        if (std::abs(std::abs(frame.water.position[q].y() - x.y()) - row) < 0.1 * row)
          allowed.push_back(colour_of(frame.water.value[q]));
      const auto [px, py] = test::pixel_of(layout.plots[0], spec.view, x);
      const Rgb got = image.at(px, py);
      INFO("particle at " << x.transpose() << ", value " << frame.water.value[k] << ", pixel (" << px << ", " << py
                          << ") of colour " << int(got.r) << "," << int(got.g) << "," << int(got.b));
      CHECK(std::find(allowed.begin(), allowed.end(), got) != allowed.end());
    }
    // Empty tank, right of the column and above the gate.
    const auto [ex, ey] = test::pixel_of(layout.plots[0], spec.view, Vec2(0.45, 0.2));
    CHECK(image.at(ex, ey) == Rgb{255, 255, 255});
  }
}

// The [render] scene table: validated key by key (file:line:column), registered with the
// scene loader so that bsmpm run and check accept it, read back from a run file, and
// overridden by the command line.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "compose/run_figures.hpp"
#include "settings/render_options.hpp"
#include "test_support.hpp"
#include "unit/render/synthetic_run.hpp"

using namespace bsmpm;
using namespace bsmpm::render;
namespace fs = std::filesystem;

namespace {

const char* kGoodTable = R"([render]
width = 640
height = 360
field = "pstar"
colormap = "jet"
solid_colormap = "viridis"
splat_scale = 1.5
colorbar = "right"
fps = 25
slowmo = 4.0
view = { min = [0.0, 0.0], max = [0.8, 0.3] }
ranges = { pstar = [0.0, 2.0], displacement = [0.0, 0.01] }
)";

RenderOptions parse(const std::string& text) { return render_options_from_scene(text, "test.toml"); }

// The SceneError for `text`, or an empty message.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("A [render] table is read key by key", "[render][options]") {
  const RenderOptions o = parse(kGoodTable);
  CHECK(o.width == 640);
  CHECK(o.height == 360);
  CHECK(o.field == "pstar");
  CHECK(o.colormap == "jet");
  CHECK(o.solid_colormap == "viridis");
  CHECK(o.splat_scale == 1.5);
  CHECK(o.colorbar == ColorBarPlacement::kRight);
  CHECK(o.fps == 25);
  CHECK(o.slowmo == 4.0);
  REQUIRE(o.view);
  CHECK(o.view->max.x() == 0.8);
  CHECK(o.ranges.at("pstar").max == 2.0);
  CHECK(o.ranges.at("displacement").max == 0.01);
  CHECK_FALSE(parse("[domain]\nmin = [0, 0]\n").width);  // no table: nothing set
}

TEST_CASE("Bad [render] values are errors naming file:line:column and the key", "[render][options]") {
  CHECK(error_of("[render]\nwidth = 8\n") == "test.toml:2:9: render.width: must be in [16, 8192] (got 8)");
  CHECK(error_of("[render]\nwidth = 640.5\n") == "test.toml:2:9: render.width: expected an integer, got a number");
  CHECK(error_of("[render]\nfield = \"density\"\n") ==
        "test.toml:2:9: render.field: must be \"pressure\", \"pstar\" or \"velocity\" (got \"density\")");
  CHECK(error_of("[render]\ncolormap = \"rainbow\"\n").rfind("test.toml:2:12: render.colormap: must be", 0) == 0);
  CHECK(error_of("[render]\nsplat_scale = 9\n").rfind("test.toml:2:15: render.splat_scale: must be in [0.5, 4]", 0) == 0);
  CHECK(error_of("[render]\nwidht = 640\n") == "test.toml:2:1: render.widht: unknown key (did you mean 'width'?)");
  CHECK(error_of("[render]\nranges = { pressure = [5.0, 1.0] }\n") ==
        "test.toml:2:23: render.ranges.pressure: expected [min, max] with max > min");
  CHECK(error_of("[render]\nranges = { presure = [0.0, 1.0] }\n").find("render.ranges.presure: unknown key") !=
        std::string::npos);
  CHECK(error_of("[render]\nview = { min = [0.0, 0.0], max = [0.0, 1.0] }\n").find("render.view.max: must exceed") !=
        std::string::npos);
  CHECK(error_of("render = 3\n") == "test.toml:1:10: render: expected a table");
}

TEST_CASE("bsmpm check validates a scene's [render] table", "[render][options][cli]") {
  const fs::path dir = test::scratch_dir("options_check");
  std::ifstream in(test::scene_path("hydrostatic_tank.toml"));
  const std::string base((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto check = [&](const std::string& render_table, std::string& err) {
    const fs::path scene = dir / "scene.toml";
    std::ofstream(scene) << base << "\n" << render_table;
    const fs::path log = dir / "check.log";
    const int status = std::system((std::string(BSMPM_EXECUTABLE) + " check " + scene.string() + " > /dev/null 2> " +
                                    log.string()).c_str());
    std::ifstream l(log);
    err.assign(std::istreambuf_iterator<char>(l), std::istreambuf_iterator<char>());
    REQUIRE(WIFEXITED(status));
    return WEXITSTATUS(status);
  };
  std::string err;
  CHECK(check(kGoodTable, err) == 0);
  CHECK(err.empty());
  const int lines = static_cast<int>(std::count(base.begin(), base.end(), '\n')) + 1;
  CHECK(check("[render]\nfps = 0\n", err) == 2);
  CHECK(err.find("scene.toml:" + std::to_string(lines + 2) + ":7: render.fps: must be in [1, 240]") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("The run's [render] table applies and the command line overrides it", "[render][options]") {
  const fs::path dir = test::scratch_dir("options_run");
  const std::string path = test::write_dam_break_run(dir, true, 3, kGoodTable);
  const RunReader run(path);

  const RunFigures from_scene(run, RenderOptions{});
  CHECK(from_scene.water_field() == Field::kPStar);
  const FrameParticles frame = from_scene.load(1);
  FigureSpec spec = from_scene.single(frame);
  CHECK(spec.width == 640);
  CHECK(spec.height == 360);
  CHECK(spec.view.max.x() == 0.8);
  CHECK(spec.placement == ColorBarPlacement::kRight);
  REQUIRE(spec.water);
  CHECK(spec.water->map.name() == "jet");
  CHECK(spec.water->range.max == 2.0);
  REQUIRE(spec.solids);
  CHECK(spec.solids->range.max == 0.01);
  // P* of the first particle: its pressure over rho g H.
  CHECK(frame.water.value[0] == Approx(1000.0 * 9.81 * (0.2 - 0.0025) / (1000.0 * 9.81 * 0.2)));

  RenderOptions cli;
  cli.field = "pressure";
  cli.water_range = ValueRange{0.0, 3000.0};
  cli.width = 320;
  const RunFigures overridden(run, cli);
  spec = overridden.single(frame);
  CHECK(overridden.water_field() == Field::kPressure);
  CHECK(spec.width == 320);
  CHECK(spec.height == 360);  // still the scene's
  CHECK(spec.water->range.max == 3000.0);
  CHECK(spec.water->map.name() == "jet");
  fs::remove_all(dir);
}

TEST_CASE("Without a given range, a first pass over the run finds it", "[render][options]") {
  const fs::path dir = test::scratch_dir("options_scan");
  const std::string path = test::write_dam_break_run(dir, true, 4);
  const RunReader run(path);
  const RunFigures figures(run, RenderOptions{});
  const FrameParticles frame = figures.load(0);
  const FigureSpec spec = figures.single(frame);
  REQUIRE(spec.water);
  REQUIRE(spec.solids);
  // Hydrostatic pressure 0 .. rho g H over a column of 40 rows: the 99.5th percentile is
  // the value of the deepest rows; 0 is included.
  CHECK(spec.water->range.min == 0.0);
  CHECK(spec.water->range.max == Approx(1000.0 * 9.81 * (0.2 - 0.0025)));
  // Displacement: 0 .. the gate tip's at the last frame, 12 mm x (0.0795/0.08)^2 (3 - ..)/2.
  const double rel = 0.0795 / 0.08;
  CHECK(spec.solids->range.max == Approx(0.012 * rel * rel * (3.0 - rel) / 2.0));
  CHECK(figures.range_notes().size() == 2);
  // Frames 0.05 s apart: two decimals; T* = t sqrt(g/H) with H = 0.2 m.
  CHECK(figures.time_label(run.frames()[2]) == "t = 0.10 s   T* = 0.70");
  CHECK(spec.header_left == "t = 0.00 s   T* = 0.00");
  CHECK(spec.header_right == "synthetic gate");
  fs::remove_all(dir);
}

// Command-line overrides (--set KEY=VALUE) of scene values.
#include <catch2/catch.hpp>

#include "step/effects/gravity.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {
SceneDescription h300(const std::vector<std::string>& overrides) {
  return load_scene(test::scene_path("lobovsky_h300.toml"), overrides);
}
}  // namespace

TEST_CASE("Overrides change numbers, strings, vectors and array entries", "[scene][override]") {
  const auto base = h300({});
  CHECK(base.cell_size == Approx(0.002));
  const auto s = h300({"grid.cell_size=0.008", "materials.water.equation_of_state=linear",
                       "bodies[0].velocity=[0.5, 0.0]", "time.end=0.1", "gravity.slope_deg=5"});
  CHECK(s.cell_size == Approx(0.008));
  CHECK(s.cells_x() == 201);  // 1.61 / 0.008 = 201.25: whole cells, 8.01 mm wide
  CHECK(s.actual_cell_size().x() == Approx(1.61 / 201));
  CHECK(std::get<WeaklyCompressibleFluid>(s.bodies[0].material).eos == EquationOfState::kLinear);
  CHECK(s.bodies[0].velocity.x() == Approx(0.5));
  CHECK(s.time.end == Approx(0.1));
  CHECK(s.effect_parameters<GravityParameters>()->slope_deg == Approx(5.0));
  // The effective scene records the overrides: read back, it is the overridden scene (the
  // shipped scene's text holds 0.008 already, in its comment and its [probes], so searching
  // the text for it proves nothing).
  const auto again = load_scene_text(s.effective_text, "effective.toml");
  CHECK(again.cell_size == 0.008);
  CHECK(again.time.end == 0.1);
  CHECK(std::get<WeaklyCompressibleFluid>(again.bodies[0].material).eos == EquationOfState::kLinear);
  CHECK(again.bodies[0].velocity == s.bodies[0].velocity);
  CHECK(again.effect_parameters<GravityParameters>()->slope_deg == 5.0);
  // Without overrides the effective scene is the scene itself.
  CHECK(load_scene_text(base.effective_text, "effective.toml").cell_size == base.cell_size);
}

TEST_CASE("A bad override names itself", "[scene][override]") {
  try {
    h300({"grid.cell_size=-1"});
    FAIL("no error");
  } catch (const SceneError& e) {
    CHECK(e.where().file == "--set grid.cell_size");
    CHECK(e.key() == "grid.cell_size");
    CHECK(std::string(e.what()).find("--set grid.cell_size: grid.cell_size: must be > 0") == 0);
  }
  CHECK_THROWS_AS(h300({"grid.cellsize=0.01"}), SceneError);  // unknown key
  CHECK_THROWS_AS(h300({"grid.cell_size"}), UsageError);      // no '='
  CHECK_THROWS_AS(h300({"bodies[3].velocity=[0,0]"}), UsageError);
  CHECK_THROWS_AS(h300({"bodies[-1].velocity=[0,0]"}), UsageError);  // no element before the first
  CHECK_THROWS_AS(h300({"grid.order.x=1"}), UsageError);      // not a table
}

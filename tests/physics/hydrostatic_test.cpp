// Water at rest in a tank (scenes/hydrostatic_tank.toml): the wall probes read rho g depth
// and the water stays at rest.
#include <catch2/catch.hpp>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Mean of a pressure probe's P column over samples with t >= t0.
double mean_pressure(const Probe& probe, double t0) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t r = 0; r < probe.row_count(); ++r)
    if (probe.row(r)[0] >= t0) {
      sum += probe.row(r)[2];
      ++n;
    }
  REQUIRE(n > 0);
  return sum / n;
}

void check_hydrostatic(const test::SceneRun& run, double velocity_bound) {
  const double rho = 1000.0, g = 9.81;
  // Probes P_depthNNN sit on the left wall at depth NNN mm below the free surface.
  for (const char* name : {"P_depth50", "P_depth100", "P_depth150"}) {
    const Probe* probe = test::find_probe(*run.sim, name);
    REQUIRE(probe != nullptr);
    const double depth = std::stoi(std::string(name).substr(7)) * 1e-3;
    const double expected = rho * g * depth;
    const double measured = mean_pressure(*probe, run.scene.time.end - 0.1);
    INFO(name << ": " << measured << " Pa against rho g depth = " << expected << " Pa");
    // 3 %: the bound; the sensor averages over a 20 mm x one-cell footprint centred
    // on the nominal depth, which is exact for a linear pressure field.
    CHECK(measured == Approx(expected).epsilon(0.03));
  }
  const Particles& ps = run.sim->particles();
  const GridInfo grid = run.sim->grid_info();
  double vmax = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    vmax = std::max(vmax, ps.v[p].norm());
    REQUIRE((ps.x[p].array() > grid.origin.array()).all());
    REQUIRE((ps.x[p].array() < grid.extent_max().array()).all());
  }
  INFO("largest particle speed " << vmax << " m/s");
  CHECK(vmax < velocity_bound);
  CHECK(run.sim->stats().clamped_positions == 0);  // no particle ever tried to leave
}

}  // namespace

TEST_CASE("Hydrostatic tank started at equilibrium stays at rest", "[physics][hydrostatic]") {
  const auto run = test::run_scene("hydrostatic_tank.toml");
  // 1 mm/s: 0.05 % of the free-fall speed sqrt(2 g H) = 2 m/s of this 0.2 m column.
  check_hydrostatic(run, 1e-3);
}

TEST_CASE("Hydrostatic tank started without stress settles to rho g depth", "[physics][hydrostatic]") {
  // Released without stress, the column compresses under its own weight and rings
  // acoustically (period 4 H / c = 25 ms) with almost no physical damping; local damping
  // (solver.local_damping = 0.1) removes the ringing so the state settles within 1 s.
  const auto run = test::run_scene("hydrostatic_tank.toml",
                                   {"bodies[0].initial_stress=none", "solver.local_damping=0.1", "time.end=1.0"});
  check_hydrostatic(run, 1e-3);
}

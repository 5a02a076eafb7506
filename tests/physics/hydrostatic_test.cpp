// Water at rest in a tank (scenes/hydrostatic_tank.toml): the wall probes read the
// hydrostatic pressure of the column and the water stays at rest.
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bounds, in one place (they depend on the fluid solver: re-measure after a
// change to it). The probes average the last 0.1 s of the run.
//
// Started at equilibrium: measured on 2026-12-01 (h = 5 mm, order 2) 490.625, 981.489 and
// 1472.58 Pa at depths 50, 100, 150 mm, within 0.01 Pa of the exact equilibrium of the
// compressed column (below), and so do the wall's reaction sensors and the floor's; the
// largest particle speed 6.5e-5 m/s. Bounds: 0.1 Pa, ten times the measured error (the
// weight of 0.01 mm of water), for the acoustic ringing left in the 0.1 s average, whose
// snapshots swing by up to 0.7 Pa; speed 2e-4 m/s, three times the measured ringing.
constexpr double kEquilibriumPressureBound = 0.1;  // Pa
constexpr double kEquilibriumSpeedBound = 2e-4;    // m/s
// Settled from a stress-free start: measured on 2026-12-01 +0.98, +1.55 and +1.92 Pa above
// the exact equilibrium at depths 150, 100 and 50 mm (0.07-0.39 %): the free surface of the
// settled column stands about 0.2 mm (h/25) higher than its compression allows (the
// pressure reads the weight of an uncompressed column: 490.62 Pa at 50 mm depth against
// 490.50 Pa of rho0 g depth). Bound: 2.5 Pa, the weight of 0.25 mm of water (h/20);
// speed: measured 2.5e-4 m/s, bound 5e-4 m/s.
constexpr double kSettledPressureBound = 2.5;  // Pa
constexpr double kSettledSpeedBound = 5e-4;    // m/s

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

// Simpson's rule for the integral of f over [a, b] (f smooth: 200 intervals are exact to
// round-off here).
double integrate(const std::function<double(double)>& f, double a, double b) {
  const int n = 200;
  const double step = (b - a) / n;
  double sum = f(a) + f(b);
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(a + k * step);
  return sum * step / 3.0;
}

const double kRho = 1000.0, kG = 9.81, kHeight = 0.2;  // the scene's water column

WeaklyCompressibleFluid scene_water(const test::SceneRun& run) {
  return std::get<WeaklyCompressibleFluid>(run.scene.bodies[0].material);
}

// Started at equilibrium, the column keeps the geometry it was seeded with, each particle
// of the compressed density rho0 / J(rho0 g s) at depth s (scene_builder), and carries the
// weight of the water above: p(d) = g int_0^d rho0 / J(rho0 g s) ds, which is
// rho0 g d (1 + rho0 g d / (2 K)) to first order in p / K.
double compressed_column_pressure(const WeaklyCompressibleFluid& water, double depth) {
  return kG * integrate([&](double s) { return kRho / water.volume_ratio(kRho * kG * s); }, 0.0, depth);
}

// Settled from an uncompressed column of height H: a material point of reference height Y
// carries the weight above it, rho0 g (H - Y), and lies at y(Y) = int_0^Y J dY'. The
// pressure at a fixed height y is that of the material point found there (bisection).
double settled_column_pressure(const WeaklyCompressibleFluid& water, double y) {
  auto position = [&](double Y) {
    return integrate([&](double s) { return water.volume_ratio(kRho * kG * (kHeight - s)); }, 0.0, Y);
  };
  double lo = y, hi = y + 0.01;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (position(mid) < y ? lo : hi) = mid;
  }
  return kRho * kG * (kHeight - 0.5 * (lo + hi));
}

enum class Reaction { kChecked, kDamped };

void check_hydrostatic(const test::SceneRun& run, const std::function<double(double)>& exact_at_height,
                       double pressure_bound, double speed_bound, Reaction reaction = Reaction::kChecked) {
  // Probes P_depthNNN (particles) and R_depthNNN (the wall's reaction, wall_reaction,
  // method.md §8, eq. S2) sit on the left wall, at the height the scene gives them (below the
  // initial free surface at kHeight); both read the same pressure, and the whole floor's reaction carries the weight
  // of all the water. The reaction measured on 2026-12-02 (equilibrium start): within 0.01 Pa
  // of the exact pressures and of the weight; the same bound as the particle probes. Not with
  // local damping, whose force at the wall's control points enters their reaction (method.md
  // §8): the settled run reads 5-8 Pa high at the side, 0.9 Pa low on the floor.
  std::vector<std::string> side_probes = {"P_depth50", "P_depth100", "P_depth150"};
  if (reaction == Reaction::kChecked) side_probes.insert(side_probes.end(), {"R_depth100", "R_depth150"});
  for (const std::string& name : side_probes) {
    const Probe* probe = test::find_probe(*run.sim, name);
    REQUIRE(probe != nullptr);
    const auto described = std::find_if(run.scene.probes.begin(), run.scene.probes.end(),
                                        [&](const ProbeDescription& d) { return d.name == name; });
    REQUIRE(described != run.scene.probes.end());
    const double height = described->position, depth = kHeight - height;  // on the left wall: y
    const double exact = exact_at_height(height);
    const double measured = mean_pressure(*probe, run.scene.time.end - 0.1);
    INFO(name << ": " << measured << " Pa against " << exact << " Pa (rho0 g depth = " << kRho * kG * depth
              << " Pa)");
    CHECK(std::abs(measured - exact) <= pressure_bound);
  }
  const Particles& ps = run.sim->particles();
  if (reaction == Reaction::kChecked) {
    const Probe* floor = test::find_probe(*run.sim, "R_floor");
    REQUIRE(floor != nullptr);
    double mass = 0.0;
    for (std::size_t p = 0; p < ps.size(); ++p) mass += ps.mass[p];
    const double width = run.scene.domain_max.x() - run.scene.domain_min.x();
    const double weight = mass * kG / width;  // per metre of floor [Pa]
    const double measured = mean_pressure(*floor, run.scene.time.end - 0.1);
    INFO("floor reaction " << measured << " Pa against the weight " << weight << " Pa");
    CHECK(std::abs(measured - weight) <= pressure_bound);
  }
  const GridInfo grid = run.sim->grid_info();
  double vmax = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    vmax = std::max(vmax, ps.v[p].norm());
    REQUIRE((ps.x[p].array() > grid.origin.array()).all());
    REQUIRE((ps.x[p].array() < grid.extent_max().array()).all());
  }
  INFO("largest particle speed " << vmax << " m/s");
  CHECK(vmax < speed_bound);
  CHECK(run.sim->stats().clamped_positions == 0);  // no particle ever tried to leave
}

}  // namespace

TEST_CASE("Hydrostatic tank started at equilibrium stays at rest", "[physics][hydrostatic]") {
  const auto run = test::run_scene("hydrostatic_tank.toml");
  const WeaklyCompressibleFluid water = scene_water(run);
  check_hydrostatic(
      run, [&](double y) { return compressed_column_pressure(water, kHeight - y); }, kEquilibriumPressureBound,
      kEquilibriumSpeedBound);
}

TEST_CASE("Hydrostatic tank started without stress settles to the weight of the water above", "[physics][hydrostatic]") {
  // Released without stress, the column compresses under its own weight and rings
  // acoustically (period 4 H / c = 25 ms) with almost no physical damping; local damping
  // (solver.local_damping = 0.1) removes the ringing so the state settles within 1 s.
  const auto run = test::run_scene("hydrostatic_tank.toml",
                                   {"bodies[0].initial_stress=none", "solver.local_damping=0.1", "time.end=1.0"});
  const WeaklyCompressibleFluid water = scene_water(run);
  check_hydrostatic(
      run, [&](double y) { return settled_column_pressure(water, y); }, kSettledPressureBound, kSettledSpeedBound,
      Reaction::kDamped);
}

TEST_CASE("Incompressible water at rest in a tank reads rho g depth and keeps its volume", "[physics][hydrostatic]") {
  // scenes/hydrostatic_tank_incompressible.toml (method.md §12), 0.5 s of 1 ms steps from
  // the hydrostatic start. Measured 2026-12-03: the side probes within 0.002 Pa of rho0 g d
  // (particles and wall reaction), the floor within 0.001 Pa of the weight; the largest
  // particle speed 6.7e-6 m/s; the water's volume (sum V0 J) and its free surface within 1e-10
  // (7.8e-11) and 1e-6 of the start. Bounds: pressures 0.5 Pa as the weakly compressible tank's (0.1 %
  // at 50 mm depth; the bound is 0.5 %), speed 5e-5 m/s (eight times the measured,
  // the bound 1e-3), volume 1e-5 and the surface 0.05 mm (1e-3 and 0.1 % of 0.2 m).
  const auto run = test::run_scene("hydrostatic_tank_incompressible.toml");
  check_hydrostatic(
      run, [&](double y) { return kRho * kG * (kHeight - y); }, 0.5, 5e-5);
  const Particles& ps = run.sim->particles();
  double volume = 0.0, volume0 = 0.0, top = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    volume += ps.volume(p);
    volume0 += ps.volume0[p];
    top = std::max(top, ps.x[p].y());
  }
  const double spacing = run.sim->bodies()[0].spacing.y();
  const double surface = top + 0.5 * spacing;  // the top row's particles stand for the water up to half a spacing above
  INFO("volume " << volume / volume0 - 1.0 << " of the start; free surface at " << surface << " m");
  CHECK(std::abs(volume / volume0 - 1.0) <= 1e-5);
  CHECK(std::abs(surface - kHeight) <= 5e-5);
}

// The Lobovsky et al. (2014) dam break, H = 300 mm (scenes/lobovsky_h300.toml), at a coarse
// grid: when the surge reaches the pressure sensor 30 mm up the downstream wall, and the
// pressure it reads once the water has piled up against the wall, against the experiment's
// run in tests/data/lobovsky2014_h300/ (docs/validation.md has the paper-resolution run).
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "diagnostics/pressure_stripes.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bounds, in one place. The test runs the scene as shipped, only coarser (its
// velocity update and volume treatment are the scene's: re-measure when they change).
// Measured on 2026-12-02 with the shipped options of then (APIC, smoothed J, particle
// shifting 0.05; docs/method.md §10; walls with skin friction C_f = 0.005, §3), h = 10 mm,
// order 2, 2 x 2 particles per cell, CFL 0.3 (2026-12-04, the shifted particles keeping their
// momentum and the sub-cell drift: arrival 2.568, plateau 0.739, ratio 1.255):
// - arrival (first T* with P* > 0.05 at z = 30 mm): 2.556 against the experiment's 2.496
//   (free slip: 2.446; 2.50 at h = 5 and 4 mm: docs/validation.md); bound |difference|
//   <= 0.10, the measured 0.06 plus 0.04 T* (7 ms);
// - plateau (mean P* over T* = 3.5-5.5): 0.737 against the experiment's 0.589, ratio 1.25
//   (free slip: 0.799, ratio 1.36; the first release: ratio 1.19). The coarse grid reads
//   high (0.67-0.69 at 4-5 mm, docs/validation.md); the time step moved the first
//   release's plateau by 8 % (CFL 0.2); bounds: ratio 1.25 +- 0.12 (measured 1.252), one
//   and a half times that effect.
constexpr double kArrivalBound = 0.10;                      // |T*_sim - T*_exp|
constexpr double kPlateauLow = 1.13, kPlateauHigh = 1.37;  // P*_sim / P*_exp

// The pressure along the bed (docs/validation.md, "Pressure stripes"): the stripe number (the
// RMS of each water particle's pressure minus the mean of its water neighbours within 2 h,
// over rho g H) of the particles less than 30 mm above the floor, over the frames in
// T* = 5.0-5.5. As shipped, with the sub-cell drift (solver.subcell_shifting = 0.0005,
// method.md §10), the columns particles bunch into at the knots even out: measured
// 0.0200 at 10 mm (2026-12-04); without the drift 0.0479 (2026-12-03, before the shift kept
// the particles' momentum: 0.0208 and 0.0484); with the fitted J's values alone read back and
// no drift (smoothed_volume_readback = "values", method.md §4; not shipped: at 8 mm it lets
// the wall probes read tension after the first impact, -0.62 P*) 0.0231 (0.0229). Bounds: the
// measured values plus 25 % (the number moves by 10-20 % from frame to frame); without the
// drift also at least the measured less 25 %, so that the test sees what the drift does.
constexpr double kStripeBoundShipped = 0.026, kStripeBoundValues = 0.029;
constexpr double kStripeOffLow = 0.036, kStripeOffHigh = 0.061;
const double kStripeBand = 0.03;  // m above the floor
const double kStripeFrom = 5.0;   // T*, to the end of the run (5.5)

const double kArrivalLevel = 0.05;                       // P*
const double kPlateauFrom = 3.5, kPlateauTo = 5.5;       // T*

struct Series {
  std::vector<double> T, P;  // T*, P*
};

// First T* at which P* exceeds the arrival level.
double arrival(const Series& s) {
  for (std::size_t k = 0; k < s.T.size(); ++k)
    if (s.P[k] > kArrivalLevel) return s.T[k];
  FAIL("the pressure never exceeds P* = " << kArrivalLevel);
  return 0.0;
}

double plateau(const Series& s) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < s.T.size(); ++k)
    if (s.T[k] >= kPlateauFrom && s.T[k] <= kPlateauTo) {
      sum += s.P[k];
      ++n;
    }
  REQUIRE(n > 10);
  return sum / n;
}

const double kPressureScale = 1000.0 * 9.81 * 0.3;  // rho g H [Pa]

// The stripe number of the summed frames (over rho g H), from enough particle samples, at
// most `bound`.
void check_stripe_number(const StripeSum& stripes, double bound) {
  const double stripe_number = stripes.rms() / kPressureScale;
  INFO("stripe number " << stripe_number << " over " << stripes.count << " particle samples");
  CHECK(stripes.count > 1000);
  CHECK(stripe_number <= bound);
}

// Runs scenes/`scene` with `overrides`, adding to `stripes` the stripe number's sums of every
// frame from T* = kStripeFrom on (the water's particles in the band).
test::SceneRun run_with_stripes(const std::vector<std::string>& overrides, StripeSum& stripes,
                                const std::string& scene = "lobovsky_h300.toml") {
  test::SceneRun run;
  run.scene = load_scene(test::scene_path(scene), overrides);
  run.sim = build_simulation(run.scene);
  RunHooks hooks;
  hooks.on_frame = [&](const Simulation& sim, double) {
    if (sim.time() * std::sqrt(9.81 / 0.3) < kStripeFrom) return;
    const Particles& ps = sim.particles();
    std::vector<char> water(ps.size());
    for (std::size_t p = 0; p < ps.size(); ++p) water[p] = is_fluid(sim.bodies()[ps.body[p]].material);
    stripes += pressure_stripes(ps.x, ps.pressure, water, StripeBand{-1.0e300, 1.0e300, 0.0, kStripeBand},
                                2.0 * sim.grid_info().cell_size.x());
  };
  run.outcome = run_to_end(*run.sim, run.scene.time, run.scene.frame_interval, hooks);
  return run;
}

Series experiment_z30() {
  std::ifstream in(test::source_path("tests/data/lobovsky2014_h300/sensor3_z30mm_run.dat"));
  REQUIRE(in.good());
  Series s;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    double T = 0.0, P = 0.0;
    if (row >> T >> P) {
      s.T.push_back(T);
      s.P.push_back(P);
    }
  }
  REQUIRE(s.T.size() > 10000);
  return s;
}

// T* and P* (columns 1 and 3) of the run's sensor P_z30.
Series simulated_z30(const Simulation& sim) {
  const Probe* probe = test::find_probe(sim, "P_z30");
  REQUIRE(probe != nullptr);
  Series s;
  for (std::size_t r = 0; r < probe->row_count(); ++r) {
    s.T.push_back(probe->row(r)[1]);
    s.P.push_back(probe->row(r)[3]);
  }
  return s;
}

}  // namespace

TEST_CASE("Lobovsky dam break at h = 10 mm: arrival and plateau at z = 30 mm against the experiment, no stripes along the bed",
          "[physics][lobovsky]") {
  // Up to T* = 5.5, the end of the plateau window (t = T* sqrt(H/g)).
  const double end = kPlateauTo * std::sqrt(0.3 / 9.81);
  StripeSum stripes;
  const auto run = run_with_stripes({"grid.cell_size=0.01", "time.end=" + std::to_string(end)}, stripes);
  const Series sim = simulated_z30(*run.sim);
  const Series exp = experiment_z30();
  const double arrival_sim = arrival(sim), arrival_exp = arrival(exp);
  const double plateau_sim = plateau(sim), plateau_exp = plateau(exp);
  INFO("arrival T* = " << arrival_sim << " against " << arrival_exp << "; plateau P* = " << plateau_sim << " against "
                       << plateau_exp << " (ratio " << plateau_sim / plateau_exp << ")");
  CHECK(std::abs(arrival_sim - arrival_exp) <= kArrivalBound);
  CHECK(plateau_sim / plateau_exp >= kPlateauLow);
  CHECK(plateau_sim / plateau_exp <= kPlateauHigh);
  check_stripe_number(stripes, kStripeBoundShipped);
}

TEST_CASE("Lobovsky dam break at h = 10 mm: reading back the smoothed J's values alone halves the stripes along the bed",
          "[physics][lobovsky]") {
  const double end = kPlateauTo * std::sqrt(0.3 / 9.81);
  StripeSum stripes;
  run_with_stripes({"grid.cell_size=0.01", "time.end=" + std::to_string(end), "solver.subcell_shifting=0",
                    "solver.smoothed_volume_readback=values"},
                   stripes);
  check_stripe_number(stripes, kStripeBoundValues);
}

TEST_CASE("Lobovsky dam break at h = 10 mm: without the sub-cell drift the columns keep their stripes along the bed",
          "[physics][lobovsky]") {
  const double end = kPlateauTo * std::sqrt(0.3 / 9.81);
  StripeSum stripes;
  run_with_stripes({"grid.cell_size=0.01", "time.end=" + std::to_string(end), "solver.subcell_shifting=0"}, stripes);
  check_stripe_number(stripes, kStripeOffHigh);
  CHECK(stripes.rms() / kPressureScale >= kStripeOffLow);
}

TEST_CASE("Lobovsky dam break, incompressible, at h = 5 mm: arrival and plateau at z = 30 mm against the experiment, "
          "the filtered volume correction's stripes along the bed",
          "[physics][lobovsky][incompressible]") {
  // scenes/lobovsky_h300_incompressible.toml (method.md §12) as shipped (J from the hats'
  // fill, volume correction 0.1 with one pass of the excess filter, eq. I3f, the multigrid
  // solve), only coarser, up to T* = 5.5. Measured 2026-12-06 at 5 mm: arrival T* = 2.490
  // against 2.496 (-0.006); plateau ratio 1.025 (at 10 mm 1.092: the coarse grid reads
  // high, as the weakly compressible model's does); stripe number 0.0208 with the filter,
  // 0.0399 without it (the excess unfiltered, as shipped before 2026-12-06).
  // Bounds: arrival as the weakly compressible test's (0.10); plateau ratio 1.025 +- 0.10,
  // the same margin as that test's for the time step's effect; the stripe number the
  // measured plus 25 % (as the tests above: it moves by 10-20 % from frame to frame), which
  // the unfiltered excess would exceed. The grid is 5 mm, not 10 mm, because at 10 mm one
  // pass takes only 13 % off the stripes (0.0268 against 0.0307), inside that margin.
  const double end = kPlateauTo * std::sqrt(0.3 / 9.81);
  StripeSum stripes;
  const auto run = run_with_stripes({"grid.cell_size=0.005", "time.end=" + std::to_string(end)}, stripes,
                                    "lobovsky_h300_incompressible.toml");
  const Series sim = simulated_z30(*run.sim);
  const Series exp = experiment_z30();
  const double arrival_sim = arrival(sim), arrival_exp = arrival(exp);
  const double ratio = plateau(sim) / plateau(exp);
  INFO("arrival T* = " << arrival_sim << " against " << arrival_exp << "; plateau ratio " << ratio
                       << "; pressure solves " << run.sim->stats().pressure.solves << ", largest residual "
                       << run.sim->stats().pressure.max_residual);
  CHECK(std::abs(arrival_sim - arrival_exp) <= kArrivalBound);
  CHECK(ratio >= 0.925);
  CHECK(ratio <= 1.125);
  CHECK(run.sim->stats().pressure.max_residual <= 1e-6);  // every solve converged to the tolerance
  check_stripe_number(stripes, 0.026);
}

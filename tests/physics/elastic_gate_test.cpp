// The elastic gate benchmark (scenes/elastic_gate.toml) at a coarse grid, short enough for
// CI, against the published curves of tests/data/walhorn_elastic_gate/; and the gate under a
// still-water load against the cantilever's static deflection, at 4 and 2 mm (1 mm hidden).
#include <catch2/catch.hpp>

#include <array>

#include <cmath>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bounds, in one place (they depend on the fluid solver and the contact: re-
// measure after a change to either).
//
// The benchmark at h = 4 mm, dt = 30 us, 5 % PIC (pinned below), with the scene's tension
// cut-off (p >= 0, docs/method.md §4), to t = 0.3 s, measured on 2026-12-02: peak tip
// displacement 44.75 mm at t = 0.250 s, on a plateau (within 0.2 mm of the peak from 0.238 to
// 0.256 s); the published peaks are 41.4-48.2 mm at 0.231-0.255 s, and the peak time is held
// to that window. Bound on the peak: 1.5 mm, a fifth of the published spread (before the
// cut-off the peak was 43.90 mm at 0.242 s: the cut-off moved it 0.85 mm; with 10 us steps it
// is 42.9 mm at 0.291 s, docs/validation.md). Mean |dx - mean of the published curves| over
// 0.1-0.3 s: measured 0.73 mm (1.02 mm before the cut-off); bound 2 mm.
constexpr double kCoarsePeak = 0.04475, kCoarsePeakBound = 0.0015;  // m
// The mean P* the face sensors (P_h20, P_h40, P_h60) read over 0.1-0.3 s: measured 0.2145,
// 0.1498, 0.0903 (the highest single samples, 12.5, 0.80 and 2.6, are impact spikes too
// sensitive to hold); bound 10 % of each. Without the tension cut-off (min_pressure removed
// from the scene) they read 0.169, 0.118 and 0.039: 21-57 % less.
const std::array<const char*, 3> kFaceProbes = {"P_h20", "P_h40", "P_h60"};
constexpr std::array<double, 3> kFaceLoads = {0.2145, 0.1498, 0.0903};
constexpr double kFaceLoadBound = 0.10;
constexpr double kCoarseCurveDeviationBound = 0.002;              // m
// Still water, pure FLIP (pinned in the scene below; 5 % PIC damps the swing away): midway
// between the first maximum and the following minimum of the tip, against the
// Euler-Bernoulli cantilever (7.44 mm), measured on 2026-12-01: 8.106 mm at 4 mm (+0.665 mm),
// 7.794 mm at 2 mm (+0.353 mm); docs/validation.md: 7.25 mm at 1 mm (-0.19 mm). The time step
// moves them by 0.01 mm (20 us at 4 mm: 8.113 mm). Bounds: the measured error plus 0.1 mm
// (1.3 % of the deflection) for solver changes.
constexpr double kStillWaterBound4mm = 0.00077, kStillWaterBound2mm = 0.00045;  // m, |midway - cantilever|

// One published curve: t [s], dx [m] of the gate's top-left corner.
struct Curve {
  std::string name;
  std::vector<double> t, dx;
  double at(double time) const {  // linear interpolation
    for (std::size_t k = 1; k < t.size(); ++k)
      if (t[k] >= time) return dx[k - 1] + (dx[k] - dx[k - 1]) * (time - t[k - 1]) / (t[k] - t[k - 1]);
    return dx.back();
  }
};

std::vector<Curve> published_curves() {
  std::vector<Curve> curves;
  for (const char* name : {"walhorn", "idelsohn", "ryzhakov", "rafiee", "li"}) {
    std::ifstream in(test::source_path(std::string("tests/data/walhorn_elastic_gate/mps_jl_") + name + ".csv"));
    REQUIRE(in.good());
    Curve c{name, {}, {}};
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream row(line);
      double t = 0.0, dx = 0.0;
      char comma = 0;
      if (row >> t >> comma >> dx) {
        c.t.push_back(t);
        c.dx.push_back(dx);
      }
    }
    REQUIRE(c.t.size() > 50);
    curves.push_back(c);
  }
  return curves;
}

struct Peak {
  double dx = -1.0, t = 0.0;
};

Peak peak_of(const std::vector<double>& t, const std::vector<double>& dx) {
  Peak p;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (dx[k] > p.dx) p = {dx[k], t[k]};
  return p;
}

// Water particles lying inside the gate's current shape. The gate is described row by
// row: for each band of one particle spacing in height, its particles span [left, right]
// (cell edges included); a water particle deeper than a quarter spacing inside a band's
// span is inside the gate.
int water_inside_gate(const Simulation& sim) {
  const Particles& ps = sim.particles();
  const Body& water = sim.bodies()[0];
  const Body& gate = sim.bodies()[1];
  const double s = gate.spacing.y();
  const int bands = 200;
  std::vector<double> left(bands, 1e9), right(bands, -1e9);
  double y0 = 1e9;
  for (std::size_t p = gate.begin; p < gate.end; ++p) y0 = std::min(y0, ps.x[p].y() - 0.5 * s);
  for (std::size_t p = gate.begin; p < gate.end; ++p) {
    const int k = static_cast<int>((ps.x[p].y() - y0) / s);
    if (k < 0 || k >= bands) continue;
    left[k] = std::min(left[k], ps.x[p].x() - 0.5 * gate.spacing.x());
    right[k] = std::max(right[k], ps.x[p].x() + 0.5 * gate.spacing.x());
  }
  int inside = 0;
  for (std::size_t p = water.begin; p < water.end; ++p) {
    const int k = static_cast<int>((ps.x[p].y() - y0) / s);
    if (k < 0 || k >= bands || left[k] > right[k]) continue;
    if (ps.x[p].x() > left[k] + 0.25 * s && ps.x[p].x() < right[k] - 0.25 * s) ++inside;
  }
  return inside;
}

}  // namespace

TEST_CASE("Elastic gate at h = 4 mm: stable, no leak, and the tip against the published curves", "[physics][gate]") {
  // 4 mm grid (the gate is 3 cells wide), 30 us steps, up to t = 0.3 s: past the impact
  // (~0.15 s) and the peak deflection (~0.24 s). The velocity update is pinned (5 % PIC).
  const SceneDescription scene = load_scene(test::scene_path("elastic_gate.toml"),
                                            {"grid.cell_size=0.004", "time.dt=3e-5", "time.end=0.3",
                                             "solver.flip=0.95", "solver.smooth_fluid_volume=true"});
  auto sim = build_simulation(scene);
  int most_inside = 0;
  long steps = 0;
  test::step_through(*sim, scene, [&](const Simulation& s) {
    // A NumericalError (non-finite state, inverted particle) would end the test here.
    if (++steps % 200 == 0) most_inside = std::max(most_inside, water_inside_gate(s));
  });
  CHECK(sim->stats().clamped_positions == 0);  // no particle tried to leave the tank
  const Particles& ps = sim->particles();
  const GridInfo grid = sim->grid_info();
  for (std::size_t p = 0; p < ps.size(); ++p) {
    REQUIRE(ps.x[p].allFinite());
    REQUIRE((ps.x[p].array() >= grid.origin.array()).all());
    REQUIRE((ps.x[p].array() <= grid.extent_max().array()).all());
  }
  CHECK(most_inside == 0);  // no water inside the obstacle

  const Probe* tip = test::find_probe(*sim, "tip");
  REQUIRE(tip != nullptr);
  std::vector<double> t, dx;
  double before_impact = 0.0;
  for (std::size_t r = 0; r < tip->row_count(); ++r) {
    t.push_back(tip->row(r)[0]);
    dx.push_back(tip->row(r)[1]);
    if (t.back() < 0.1) before_impact = std::max(before_impact, std::abs(dx.back()));
  }
  CHECK(before_impact < 1e-4);  // untouched before the water arrives

  // The published curves: their peaks, and their mean, against which the whole curve from
  // 0.1 s (before the impact) to 0.3 s is compared.
  const auto curves = published_curves();
  double lowest_peak = 1.0, highest_peak = 0.0, earliest = 1.0, latest = 0.0;
  for (const Curve& c : curves) {
    const Peak p = peak_of(c.t, c.dx);
    lowest_peak = std::min(lowest_peak, p.dx);
    highest_peak = std::max(highest_peak, p.dx);
    earliest = std::min(earliest, p.t);
    latest = std::max(latest, p.t);
  }
  double deviation = 0.0;
  int samples = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] < 0.1) continue;
    double mean = 0.0;
    for (const Curve& c : curves) mean += c.at(t[k]) / curves.size();
    deviation += std::abs(dx[k] - mean);
    ++samples;
  }
  REQUIRE(samples > 100);
  deviation /= samples;
  const Peak peak = peak_of(t, dx);
  INFO("tip: peak dx = " << peak.dx * 1e3 << " mm at t = " << peak.t << " s; published peaks " << lowest_peak * 1e3
                         << "-" << highest_peak * 1e3 << " mm at " << earliest << "-" << latest
                         << " s; mean deviation from the published mean over 0.1-0.3 s " << deviation * 1e3 << " mm");
  // Within the published spread (the accuracy band of this benchmark, tests/data/README.md) ...
  CHECK(peak.dx >= lowest_peak);
  CHECK(peak.dx <= highest_peak);
  CHECK(peak.t >= earliest);
  CHECK(peak.t <= latest);
  // ... and at the measured values (kCoarsePeak).
  CHECK(std::abs(peak.dx - kCoarsePeak) <= kCoarsePeakBound);
  CHECK(deviation <= kCoarseCurveDeviationBound);

  // The face probes read the water's load: the scene's tension cut-off (min_pressure = 0)
  // keeps every sample >= 0 by construction, so what is checked is the load itself, the mean
  // P* each face sensor reads from before the impact to after the peak (kFaceLoads).
  for (std::size_t k = 0; k < kFaceProbes.size(); ++k) {
    const Probe* probe = test::find_probe(*sim, kFaceProbes[k]);
    REQUIRE(probe != nullptr);
    double sum = 0.0;
    int samples = 0;
    for (std::size_t r = 0; r < probe->row_count(); ++r)
      if (probe->row(r)[0] >= 0.1 && probe->row(r)[0] <= 0.3) {
        sum += probe->row(r)[3];
        ++samples;
      }
    REQUIRE(samples > 100);
    INFO(kFaceProbes[k] << ": mean P* over 0.1-0.3 s " << sum / samples << ", measured " << kFaceLoads[k]);
    CHECK(std::abs(sum / samples - kFaceLoads[k]) <= kFaceLoadBound * kFaceLoads[k]);
  }
}

namespace {

// The benchmark's gate (12 x 80 mm, E = 1 MPa, nu = 0, clamped base) holding back a column
// of still water as high as itself, frictionless contact, grid h. The load is the
// triangular hydrostatic one, w(y) = rho g (L - y), whose static tip deflection for a
// cantilever is w0 L^4 / (30 E I) with w0 = rho g L, I = t^3 / 12 (plane strain, nu = 0).
// Applied suddenly, the gate swings about it: the midpoint of the first maximum and the
// following minimum estimates the static deflection.
struct StillWaterSwing {
  double highest = -1.0, lowest = 1.0, t_high = 0.0;
  double middle() const { return 0.5 * (highest + lowest); }
};

StillWaterSwing still_water_gate(double h) {
  const SceneDescription scene = load_scene(test::fixture_path("still_water_gate.toml"), {"grid.cell_size=" + std::to_string(h)});
  auto sim = build_simulation(scene);
  test::step_through(*sim, scene, [](const Simulation&) {});
  const Probe* tip = test::find_probe(*sim, "tip");
  REQUIRE(tip != nullptr);
  StillWaterSwing s;
  for (std::size_t r = 0; r < tip->row_count(); ++r) {
    const double t = tip->row(r)[0], dx = tip->row(r)[1];
    if (t > 0.05 && t < 0.15 && dx > s.highest) {
      s.highest = dx;
      s.t_high = t;
    }
    if (t > 0.15 && dx < s.lowest) s.lowest = dx;
  }
  return s;
}

const double kStaticTip = 1000.0 * 9.81 * 0.08 * std::pow(0.08, 4) / (30.0 * 1.0e6 * std::pow(0.012, 3) / 12.0);  // 7.44 mm

void check_swing(const StillWaterSwing& s, double h, double bound) {
  INFO("h = " << h * 1e3 << " mm: tip swings between " << s.lowest * 1e3 << " and " << s.highest * 1e3
              << " mm (first maximum at t = " << s.t_high << " s); midway " << s.middle() * 1e3 << " mm against "
              << kStaticTip * 1e3 << " mm");
  CHECK(s.highest > 1.5 * kStaticTip);  // a sudden load overshoots (undamped: up to twice)
  CHECK(s.highest < 2.0 * kStaticTip);
  CHECK(std::abs(s.middle() - kStaticTip) <= bound);
}

}  // namespace

TEST_CASE("A gate suddenly loaded by still water swings about the cantilever's deflection, closer on a finer grid",
          "[physics][gate][contact][convergence]") {
  // The beam theory leaves out shear deformation of a beam 1/6.7 as thick as long (+2 % by
  // Timoshenko), the water level falling as the gate yields and water spilling over its top;
  // the grid error must still fall from 4 to 2 mm (bounds: kStillWaterBound4mm).
  const StillWaterSwing coarse = still_water_gate(0.004), fine = still_water_gate(0.002);
  check_swing(coarse, 0.004, kStillWaterBound4mm);
  check_swing(fine, 0.002, kStillWaterBound2mm);
  CHECK(std::abs(fine.middle() - kStaticTip) < std::abs(coarse.middle() - kStaticTip));
}

TEST_CASE("Still-water gate at 1 mm (long)", "[.][physics][gate][convergence]") {
  const StillWaterSwing fine = still_water_gate(0.002), finest = still_water_gate(0.001);
  check_swing(finest, 0.001, kStillWaterBound2mm);  // docs/validation.md: 7.25 mm
  CHECK(std::abs(finest.middle() - kStaticTip) < std::abs(fine.middle() - kStaticTip));
}

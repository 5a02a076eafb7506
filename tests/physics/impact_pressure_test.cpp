// Impact pressure at a wall (docs/method.md §10, docs/validation.md "Jet on a wall"):
// a plane jet against the steady stagnation flow it must form, and the Lobovsky dam break's
// first impact, whose wall probes must not read tension.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

struct WindowStats {
  double mean = 0.0, deviation = 0.0;
};

// Mean and standard deviation of the probe's pressure column P over t in (t0, t1).
WindowStats pressure_over(const Probe& probe, double t0, double t1) {
  double sum = 0.0, squares = 0.0;
  int n = 0;
  for (std::size_t r = 0; r < probe.row_count(); ++r) {
    const double* row = probe.row(r);
    if (row[0] <= t0 || row[0] >= t1) continue;
    sum += row[2];
    squares += row[2] * row[2];
    ++n;
  }
  REQUIRE(n > 100);
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, squares / n - mean * mean))};
}

// The jet of scenes/jet_on_wall*.toml: density, speed, width and Bernoulli's stagnation pressure.
namespace jet {
constexpr double rho = 1000.0, U = 2.0, b = 0.05, p0 = 0.5 * rho * U * U;
}

// The jet's floor probes (scenes/jet_on_wall*.toml: 0, 15, 30, 45 and 60 mm from the axis)
// over t = 0.06-0.12 s, the steady stagnation flow, and the momentum flux through them: the
// trapezoid over |x| <= 1.2 b (both sides).
struct JetReading {
  std::vector<WindowStats> at;
  double integral = 0.0;
};

JetReading read_jet(const Simulation& sim) {
  const double p0 = jet::p0, spacing = 0.015;
  JetReading r;
  for (const char* name : {"P_x400", "P_x415", "P_x430", "P_x445", "P_x460"}) {
    const Probe* probe = test::find_probe(sim, name);
    REQUIRE(probe != nullptr);
    r.at.push_back(pressure_over(*probe, 0.06, 0.12));
    UNSCOPED_INFO(name << ": mean " << r.at.back().mean / p0 << " p0, deviation " << r.at.back().deviation / p0 << " p0");
  }
  for (std::size_t k = 1; k < r.at.size(); ++k) r.integral += 0.5 * (r.at[k - 1].mean + r.at[k].mean) * spacing;
  r.integral *= 2.0;
  return r;
}

}  // namespace

TEST_CASE("A plane jet on a wall: stagnation pressure and momentum flux", "[physics][impact]") {
  // scenes/jet_on_wall.toml: b = 50 mm, U = 2 m/s, h = 2.5 mm (20 cells across the jet),
  // no gravity. Steady stagnation flow of a free jet: p = rho U^2 / 2 on the axis, falling
  // within about a jet width; the whole wall carries rho U^2 b.
  const auto run = test::run_scene("jet_on_wall.toml");
  using jet::rho, jet::U, jet::b, jet::p0;
  const JetReading reading = read_jet(*run.sim);
  const auto& at = reading.at;
  // On the axis. Measured 0.598 p0 (2026-12-04: APIC + smoothed J + shifting, the shipped
  // options; the shifted particles keep their momentum, method.md §10). Before, the shifted
  // particles took their affine field's velocity, which added 4 % of the floor's momentum
  // over the run: the floor then carried 1.11 rho U^2 b and the axis read 0.70 p0, through
  // the probes 0.77 rho U^2 b; the particles read the same share of the wall's load then as
  // now (0.69). The solver of the first release read 0.57 p0, FLIP with 5 % PIC 0.84 p0 but
  // swinging by 0.29 p0. What is left of the deficit is how the particles next to the wall
  // carry pressure (docs/validation.md, "Jet on a wall"). Bound: the measured value less
  // 0.08 p0, about one standard deviation of the axis signal.
  CHECK(at[0].mean > 0.52 * p0);
  CHECK(at[0].mean < 1.05 * p0);  // never above Bernoulli (+5 %: compressibility, M = 0.06)
  // Steadiness: measured 0.081 p0 (the first release: 0.29 p0). Bound about twice the measured.
  CHECK(at[0].deviation < 0.15 * p0);
  // Pressure falls away from the axis: at 0.9 b it is below its value at 0.3 b.
  CHECK(at[3].mean < at[1].mean);
  // Momentum flux through the probes: the trapezoid over |x| <= 1.2 b (both sides), a part
  // of the wall's rho U^2 b (pressure is positive everywhere on it, so below 1). Measured
  // 0.686 (0.77 with the affine shift, the first release 0.61); bound the measured less 0.07.
  INFO("integral " << reading.integral / (rho * U * U * b) << " rho U^2 b");
  CHECK(reading.integral > 0.62 * rho * U * U * b);
  CHECK(reading.integral < 1.0 * rho * U * U * b);
  // The floor's reaction (wall_reaction over the whole floor, 0.8 m) carries the jet's
  // momentum flux rho U^2 b in the steady state. Measured 1.008 rho U^2 b (1.11 with the
  // affine shift, 1.03 without shifting); bound 0.04 either side of rho U^2 b, twice the
  // measured departure and the window's unsteadiness.
  const Probe* floor = test::find_probe(*run.sim, "R_floor");
  REQUIRE(floor != nullptr);
  const double reaction = pressure_over(*floor, 0.06, 0.12).mean * 0.8;
  INFO("floor reaction " << reaction / (rho * U * U * b) << " rho U^2 b");
  CHECK(reaction > 0.96 * rho * U * U * b);
  CHECK(reaction < 1.04 * rho * U * U * b);
}

TEST_CASE("Incompressible water: a plane jet on a wall, stagnation pressure and momentum flux",
          "[physics][impact][incompressible]") {
  // scenes/jet_on_wall_incompressible.toml (method.md §12): the jet above with the pressure
  // of the projection, at steps of 0.13-0.37 ms. The bounds are the weakly compressible
  // test's. Measured 2026-12-04 with particle_shifting = 0.2, the scene's, the shifted
  // particles keeping their momentum (method.md §10): 0.594 p0 on the axis (bound 0.03 below
  // it), deviation 0.073 p0, 0.685 rho U^2 b through the probes (bound 0.026 below it), the
  // floor's reaction 1.017 rho U^2 b, 793 solves; with the affine shift before (2026-12-03)
  // 0.650 p0, 0.726 and a reaction of 1.09, inflated by the shift's momentum. With the weakly
  // compressible scene's 0.05 (a drift per step, at steps 6-17 times longer) the particles
  // crowded next to the wall, up to 4 times the water a corner's hat holds, the particle
  // quadrature overstated the water there and the
  // pressure that balanced the jet read 0.44 p0 on the axis, 0.63 through the probes, while
  // the floor's reaction read 1.06 rho U^2 b (method.md §12, "Particle shifting").
  const auto run = test::run_scene("jet_on_wall_incompressible.toml");
  using jet::rho, jet::U, jet::b, jet::p0;
  const JetReading reading = read_jet(*run.sim);
  const auto& at = reading.at;
  INFO("integral " << reading.integral / (rho * U * U * b) << " rho U^2 b; pressure solves "
                   << run.sim->stats().pressure.solves << ", largest residual " << run.sim->stats().pressure.max_residual);
  CHECK(at[0].mean > 0.56 * p0);
  // Incompressible: the steady stagnation pressure is Bernoulli's p0 at most; +5 % for the
  // window's unsteadiness (deviation 0.07 p0).
  CHECK(at[0].mean < 1.05 * p0);
  CHECK(at[0].deviation < 0.15 * p0);
  CHECK(at[3].mean < at[1].mean);
  CHECK(reading.integral > 0.66 * rho * U * U * b);
  CHECK(reading.integral < 1.0 * rho * U * U * b);
  // The floor's reaction (wall_reaction over the whole floor, 0.8 m) carries the jet's
  // momentum flux rho U^2 b in the steady state: measured 1.017 rho U^2 b; bound 0.04 either
  // side of rho U^2 b, as the weakly compressible test's.
  const Probe* floor = test::find_probe(*run.sim, "R_floor");
  REQUIRE(floor != nullptr);
  const double reaction = pressure_over(*floor, 0.06, 0.12).mean * 0.8;
  INFO("floor reaction " << reaction / (rho * U * U * b) << " rho U^2 b");
  CHECK(reaction > 0.96 * rho * U * U * b);
  CHECK(reaction < 1.04 * rho * U * U * b);
}

TEST_CASE("Dam break: the wall probes read no tension after first contact", "[physics][impact]") {
  // scenes/lobovsky_h300.toml (shipped options) at h = 8 mm up to T* = 3.4, through the
  // first impact and the run-up. Water in the experiment carries no tension (its lowest
  // sample after contact is -0.01 P* at 30 mm and -0.04 at 80 mm); the bound is
  // -0.1 P*. Measured (2026-12-02, walls with skin friction): 0.000 at 30 mm and -0.040 at
  // 80 mm (free slip: 0.000 at both; the first release: -2.07 and -1.56).
  const auto run = test::run_scene("lobovsky_h300.toml", {"grid.cell_size=0.008", "time.end=0.6"});
  for (const char* name : {"P_z30", "P_z80"}) {
    const Probe* probe = test::find_probe(*run.sim, name);
    REQUIRE(probe != nullptr);
    const auto lowest = test::lowest_after_contact(*probe, 0.05);
    REQUIRE(lowest);  // the water reached it
    INFO(name << ": lowest P* after contact " << *lowest);
    CHECK(*lowest > -0.1);
  }
}

TEST_CASE("A tension cut-off bounds the water's J too, so a splashing run goes on", "[physics][impact]") {
  // scenes/elastic_gate.toml at h = 4 mm, 30 us steps, to t = 0.18 s (the surge strikes the
  // gate at 0.14 s and sprays up its face) with materials.water.min_pressure = 0 (method.md
  // §4; the scene's value since 2026-12-02, set here so that the test holds the option). With
  // the cut-off on p alone (measured 2026-12-02) the water's J reached 1.07 by then (800
  // particles above 1.001), and at 2 and 1 mm the spray's J grew until the run stopped on the
  // density guard; with J held at J(p_min) = 1 no water particle is stretched and none carries
  // tension, and the face probes read none.
  const auto run = test::run_scene("elastic_gate.toml", {"grid.cell_size=0.004", "time.dt=3e-5", "time.end=0.18",
                                                         "materials.water.min_pressure=0"});
  const Particles& ps = run.sim->particles();
  double highest_J = 0.0, lowest_p = 1e300;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    if (ps.body[p] != 0) continue;  // the water
    highest_J = std::max(highest_J, ps.J[p]);
    lowest_p = std::min(lowest_p, ps.pressure[p]);
  }
  INFO("water: highest J " << highest_J << ", lowest p " << lowest_p << " Pa");
  CHECK(highest_J <= 1.0);
  CHECK(lowest_p >= 0.0);
  for (const char* name : {"P_h20", "P_h40", "P_h60"}) {
    const Probe* probe = test::find_probe(*run.sim, name);
    REQUIRE(probe != nullptr);
    const auto lowest = test::lowest_after_contact(*probe, 0.05);
    REQUIRE(lowest);
    INFO(name << ": lowest P* after contact " << *lowest);
    CHECK(*lowest >= 0.0);
  }
}

namespace {

// The floor's impulse (the wall_reaction probe R_floor over the whole floor, integrated over
// the run) and the vertical momentum the jet gained, both in N s/m.
struct MomentumBalance {
  double impulse = 0.0, gained = 0.0;
};

MomentumBalance floor_balance(const std::vector<std::string>& overrides) {
  const auto run = test::run_scene("jet_on_wall.toml", overrides);
  const Probe* floor = test::find_probe(*run.sim, "R_floor");
  REQUIRE(floor != nullptr);
  const double length = 0.8;  // the probe's face: the whole floor
  MomentumBalance b;
  for (std::size_t r = 1; r < floor->row_count(); ++r)
    b.impulse += floor->row(r)[2] * length * (floor->row(r)[0] - floor->row(r - 1)[0]);
  const Particles& ps = run.sim->particles();
  double momentum = 0.0, mass = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    momentum += ps.mass[p] * ps.v[p].y();
    mass += ps.mass[p];
  }
  b.gained = momentum - mass * -2.0;  // the jet started at v = (0, -2) m/s
  REQUIRE(b.impulse > 20.0);  // the jet has struck: 0.1 s of rho U^2 b = 200 N/m
  return b;
}

std::ostream& operator<<(std::ostream& out, const MomentumBalance& b) {
  return out << "floor impulse " << b.impulse << " N s/m, momentum gained " << b.gained
             << " N s/m, relative difference " << (b.impulse - b.gained) / b.impulse;
}

}  // namespace

TEST_CASE("The floor's reaction is the momentum the jet loses", "[physics][impact]") {
  // The wall_reaction probe (method.md §8, eq. S2) over the whole floor, integrated over the
  // run, against the change of the water's vertical momentum: without gravity the floor is
  // the only force on it, and the transfers (APIC) conserve momentum, so the two agree to
  // round-off; so does the particle shifting of the shipped scene, whose shifted particles keep
  // their velocity (method.md §10). Measured 2026-12-02 without shifting: impulse 25.5214 N s/m
  // over 0.125 s, relative difference 2.2e-7; bound ten times that, 2e-6, with shifting too.
  SECTION("the scene as shipped, shifting on") {
    const MomentumBalance b = floor_balance({});
    INFO(b);
    CHECK(std::abs(b.impulse - b.gained) <= 2e-6 * b.impulse);
  }
  SECTION("without shifting") {
    const MomentumBalance b = floor_balance({"solver.particle_shifting=0"});
    INFO(b);
    CHECK(std::abs(b.impulse - b.gained) <= 2e-6 * b.impulse);
  }
  SECTION("a shifted particle taking its affine field's velocity does not conserve it") {
    // shifting_velocity = "affine" (v_p += C_p dx): the shifts add momentum towards the floor;
    // measured 2026-12-02, the reaction 4 % above the momentum lost; bound 1 %, what the
    // balance above would have to miss by to pass unnoticed.
    const MomentumBalance b = floor_balance({"solver.shifting_velocity=affine"});
    INFO(b);
    CHECK(std::abs(b.impulse - b.gained) > 0.01 * b.impulse);
  }
}

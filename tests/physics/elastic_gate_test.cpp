// The elastic gate benchmark (scenes/elastic_gate.toml) at a coarse grid, short enough for
// CI: the run stays numerically sound and the gate bends the way the water pushes it.
#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

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

TEST_CASE("Elastic gate at h = 4 mm: stable, no leak, tip pushed downstream", "[physics][gate]") {
  // 4 mm grid (the gate is 3 cells wide), 30 us steps, up to t = 0.3 s: past the impact
  // (~0.15 s) and the peak deflection (~0.23 s).
  const SceneDescription scene = load_scene(test::scene_path("elastic_gate.toml"),
                                            {"grid.cell_size=0.004", "time.dt=3e-5", "time.end=0.3"});
  auto sim = build_simulation(scene);
  int most_inside = 0;
  long steps = 0;
  test::step_through(*sim, scene, [&](const Simulation& s) {
    // A NumericalError (non-finite state, inverted particle) would end the test here.
    if (++steps % 200 == 0) most_inside = std::max(most_inside, water_inside_gate(s));
  });
  CHECK(sim->time() >= 0.3);
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
  double peak = -1.0, peak_time = 0.0, before_impact = 0.0;
  for (std::size_t r = 0; r < tip->row_count(); ++r) {
    const double t = tip->row(r)[0], dx = tip->row(r)[1];
    if (t < 0.1) before_impact = std::max(before_impact, std::abs(dx));
    if (dx > peak) {
      peak = dx;
      peak_time = t;
    }
  }
  INFO("tip: peak dx = " << peak * 1e3 << " mm at t = " << peak_time << " s");
  CHECK(before_impact < 1e-4);  // untouched before the water arrives
  // Pushed downstream by several centimetres (published peaks 41-48 mm at 0.23-0.26 s; the
  // coarse grid is not held to them here, only to the direction and order of magnitude).
  CHECK(peak > 0.02);
  CHECK(peak < 0.08);
  CHECK(peak_time > 0.15);
}

TEST_CASE("A gate suddenly loaded by still water swings about the cantilever's static deflection",
          "[physics][gate][contact]") {
  // The benchmark's gate (12 x 80 mm, E = 1 MPa, nu = 0, clamped base) holding back a
  // column of still water as high as itself, frictionless contact, h = 2 mm. The load is
  // the triangular hydrostatic one, w(y) = rho g (L - y), whose static tip deflection for a
  // cantilever is w0 L^4 / (30 E I) with w0 = rho g L, I = t^3 / 12 (plane strain, nu = 0).
  // Applied suddenly, the gate swings about it: the midpoint of the first maximum and the
  // following minimum estimates the static deflection.
  const std::string text = R"(
[domain]
min = [0.0, 0.0]
max = [0.2, 0.12]
[grid]
cell_size = 0.002
[time]
end = 0.25
dt = 1.0e-5
[solver]
smooth_fluid_volume = true
[materials.water]
type = "fluid"
density = 1000.0
bulk_modulus = 1.0e6
viscosity = 1.0e-3
[materials.gate]
type = "elastic"
density = 2500.0
youngs_modulus = 1.0e6
poisson_ratio = 0.0
[[bodies]]
name = "water"
material = "water"
shape = { type = "rectangle", min = [0.0, 0.0], max = [0.05, 0.08] }
initial_stress = "hydrostatic"
[[bodies]]
name = "gate"
material = "gate"
shape = { type = "rectangle", min = [0.05, 0.0], max = [0.062, 0.08] }
[[bodies.clamp]]
min = [0.05, 0.0]
max = [0.062, 0.0]
[[contacts]]
bodies = ["water", "gate"]
type = "frictionless"
[[probes]]
name = "tip"
type = "material_point"
body = "gate"
point = [0.05, 0.08]
)";
  const SceneDescription scene = load_scene_text(text, "still_water_gate.toml");
  auto sim = build_simulation(scene);
  test::step_through(*sim, scene, [](const Simulation&) {});
  const Probe* tip = test::find_probe(*sim, "tip");
  REQUIRE(tip != nullptr);
  double highest = -1.0, lowest = 1.0, t_high = 0.0;
  for (std::size_t r = 0; r < tip->row_count(); ++r) {
    const double t = tip->row(r)[0], dx = tip->row(r)[1];
    if (t > 0.05 && t < 0.15 && dx > highest) {
      highest = dx;
      t_high = t;
    }
    if (t > 0.15 && dx < lowest) lowest = dx;
  }
  const double L = 0.08, thickness = 0.012, E = 1.0e6, w0 = 1000.0 * 9.81 * L;
  const double static_tip = w0 * std::pow(L, 4) / (30.0 * E * std::pow(thickness, 3) / 12.0);  // 7.44 mm
  const double middle = 0.5 * (highest + lowest);
  INFO("tip swings between " << lowest * 1e3 << " and " << highest * 1e3 << " mm (first maximum at t = " << t_high
                             << " s); midway " << middle * 1e3 << " mm against " << static_tip * 1e3 << " mm");
  CHECK(highest > 1.5 * static_tip);  // a sudden load overshoots (undamped: up to twice)
  CHECK(highest < 2.0 * static_tip);
  // Measured: 7.79 mm at h = 2 mm (8.11 at 4 mm, 7.25 at 1 mm). 8 % covers what beam theory
  // leaves out: shear deformation of a beam 1/6.7 as thick as long (a few per cent), the
  // water level falling as the gate yields, and water spilling over its top.
  CHECK(std::abs(middle - static_tip) < 0.08 * static_tip);
}

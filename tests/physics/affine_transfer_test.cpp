// The affine particle velocity (docs/method.md §10, solver.velocity_update = "apic") against
// what Jiang et al. (2015) prove of it: the transfers keep angular momentum, which PIC
// dissipates. A spinning elastic disk, free in space, must keep its spin.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "scene/scene_loader.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

constexpr double kOmega = 2.0;  // rad/s: rim speed 0.4 m/s, 4 % of the P-wave speed
const Vec2 kCentre(0.5, 0.5);

// Angular momentum about the disk's centre: sum m (x - c) x v, plus with APIC the affine
// field's own, m (C D)_yx - m (C D)_xy with D = h^2/4 I for quadratic splines inside the grid.
double angular_momentum(const Particles& ps, double h, bool affine) {
  double L = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const Vec2 r = ps.x[p] - kCentre;
    L += ps.mass[p] * (r.x() * ps.v[p].y() - r.y() * ps.v[p].x());
    if (affine) L += ps.mass[p] * 0.25 * h * h * (ps.C[p](1, 0) - ps.C[p](0, 1));
  }
  return L;
}

// Runs the disk spun up to kOmega for 0.5 s (about 800 steps) and returns L(end) / L(0).
double spin_kept(const std::vector<std::string>& overrides, bool affine) {
  const SceneDescription scene = load_scene(test::fixture_path("spinning_disk.toml"), overrides);
  auto sim = build_simulation(scene);
  // Rigid rotation, v = omega e_z x (x - c), and its affine field C = omega [[0, -1], [1, 0]].
  auto& ps = const_cast<Particles&>(sim->particles());
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const Vec2 r = ps.x[p] - kCentre;
    ps.v[p] = kOmega * Vec2(-r.y(), r.x());
    if (affine) ps.C[p] << 0.0, -kOmega, kOmega, 0.0;
  }
  const double h = 0.025;
  const double start = angular_momentum(ps, h, affine);
  test::step_through(*sim, scene, [](Simulation&) {});
  REQUIRE(sim->stats().clamped_positions == 0);
  return angular_momentum(sim->particles(), h, affine) / start;
}

}  // namespace

TEST_CASE("A spinning disk keeps its angular momentum with APIC, and loses it with PIC", "[physics][apic]") {
  // Measured: APIC keeps 1 - 3.3e-7 (the transfers conserve it exactly, Jiang et al. 2015
  // §5.3; what is left is the step's position update, O(dt^2)); PIC (the FLIP update with
  // solver.flip = 0) keeps -0.003: each of its ~800 transfers removes about h^2/4 / <r^2>.
  // Bounds: APIC within 1e-6 (three times the measured); PIC below 0.5.
  const double apic = spin_kept({"solver.velocity_update=apic"}, true);
  const double pic = spin_kept({"solver.flip=0"}, false);
  INFO("L(end)/L(0): APIC " << apic << ", PIC " << pic);
  CHECK(std::abs(apic - 1.0) < 1e-6);
  CHECK(pic < 0.5);
}

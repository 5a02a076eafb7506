// The walls' skin friction (docs/method.md §3, eq. W1) against its analytic solution: a layer
// of viscous fluid, depth d = 20 mm and 0.8 m long, slides along the floor of a tank at
// U0 = 1 m/s without gravity (C_f = 0.02, mu = 40 Pa s, 0.3 s). The
// floor's traction rho C_f U^2 is the only force along the floor, so while the layer moves
// as one (its viscosity carries the floor's shear through the depth in d^2 / nu = 0.01 s)
// its mean velocity follows dU/dt = -C_f U^2 / d:
//   U(t) = U0 / (1 + C_f U0 t / d).
// Free slip keeps U = U0; the law's force per length of wall does not depend on the grid,
// so two grids must give the same decay.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "core/format.hpp"
#include "step/bsmpm_simulation.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bound, in one place (re-measure after a change to the walls or the fluid
// solver). Measured on 2026-12-02 (order 2, 2 x 2 particles per cell, the default solver),
// U(0.3 s) / U_analytic = 1.0041 at h = d/4 and 1.0088 at h = d/8; free slip keeps
// U = U0 to 2e-11 (kFreeSlipBound). The layer is not quite a plug: its ends are slowed first and thicken,
// which takes wall from the law; the excess is an end effect (a layer 0.3 m long gives
// 1.009 and 1.022), and the viscous lag of the floor's velocity behind the mean,
// tau d / (3 mu), is 0.3 % of U. Bound: 2 % (the measurement plus 1.1 %); the law with
// the wrong length or density (a factor 2 on C_f: 0.625 U0) or free slip (1.30 times the
// analytic) is far outside it.
constexpr double kBound = 0.02;
// Free slip keeps U0: |U / U0 - 1| measured 1.7e-11 (h = d/4); bound about ten times that.
constexpr double kFreeSlipBound = 2e-10;

const double kDepth = 0.02, kU0 = 1.0, kSkinFriction = 0.02, kEnd = 0.3;

// Mean velocity along the floor (total momentum over total mass) at the scene's end.
double mean_velocity_at_end(double cell_size, double skin_friction) {
  const SceneDescription scene = load_scene(test::fixture_path("sliding_layer.toml"),
                 {"grid.cell_size=" + shortest(cell_size), "domain.walls.skin_friction=" + shortest(skin_friction)});
  auto sim = build_simulation(scene);
  auto* bsmpm = dynamic_cast<BsmpmSimulation<2>*>(sim.get());
  REQUIRE(bsmpm != nullptr);
  Particles& ps = bsmpm->state().particles;
  for (std::size_t p = 0; p < ps.size(); ++p) ps.v[p] = Vec2(kU0, 0.0);
  test::step_through(*sim, scene, [](const Simulation&) {});
  double momentum = 0.0, mass = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    momentum += ps.mass[p] * ps.v[p].x();
    mass += ps.mass[p];
  }
  return momentum / mass;
}

}  // namespace

TEST_CASE("Skin friction slows a layer sliding along the floor as U0 / (1 + C_f U0 t / d), on any grid",
          "[physics][walls]") {
  const double exact = kU0 / (1.0 + kSkinFriction * kU0 * kEnd / kDepth);  // 0.769
  for (double h : {kDepth / 4, kDepth / 8}) {
    const double u = mean_velocity_at_end(h, kSkinFriction);
    INFO("h = " << h << ": U(t) = " << u << ", analytic " << exact << ", ratio " << u / exact);
    CHECK(std::abs(u / exact - 1.0) < kBound);
  }
  // Without it the layer keeps its speed: the decay above is the law's, not the solver's.
  const double free_slip = mean_velocity_at_end(kDepth / 4, 0.0);
  INFO("free slip: U(t) / U0 - 1 = " << free_slip / kU0 - 1.0);
  CHECK(std::abs(free_slip / kU0 - 1.0) < kFreeSlipBound);
}

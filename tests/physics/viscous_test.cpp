// Viscous flow against an analytic solution: a shear flow u(y) = U cos(pi y / H) in a tank
// filled with a viscous fluid, no gravity. The momentum equation reduces to du/dt = nu u_yy,
// whose solution with free-slip floor and lid (du/dy = 0 there) is the decaying profile
// u(y, t) = U cos(pi y / H) exp(-nu (pi / H)^2 t) (the transient shear flow between two
// plates; Couette and Poiseuille flows need periodic ends or a moving wall, which the tank
// does not have). The flow turns at the tank's ends; at 3 H from them (the middle of a tank
// 6 H long) its effect has decayed like exp(-3 pi).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "step/bsmpm_simulation.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bounds, in one place (they depend on the fluid solver: re-measure after a
// change to it). Measured on 2026-12-01 (h = H/20, order 2, 2 x 2 particles per cell, pure
// FLIP pinned, CFL 0.3), after one decay time (t = 0.1 s, exp(-nu k^2 t) = 0.373):
// - amplitude of the cos mode in the middle third of the tank 1.017 times the analytic;
// - the profile averaged along x over the middle third, row by row of particles: largest
//   deviation from the analytic 1.1 % of U (next to the floor and the lid).
// Single particles deviate by up to 4 % of U: the tank's ends stop the flow at once and send
// pressure waves along it. Bounds: amplitude 3 %, profile 2 % of U (the measurement plus
// about a third of those waves, which the averages do not fully cancel).
constexpr double kAmplitudeBound = 0.03;  // relative
constexpr double kProfileBound = 0.02;    // of U

const double kH = 0.1, kL = 0.6, kU = 0.01, kMu = 10.0, kRho = 1000.0;  // nu = 0.01 m2/s

}  // namespace

TEST_CASE("A viscous shear flow decays as nu (pi/H)^2 with its cosine profile", "[physics][viscous]") {
  const SceneDescription scene = load_scene(test::fixture_path("shear_tank.toml"));
  auto sim = build_simulation(scene);
  auto* bsmpm = dynamic_cast<BsmpmSimulation<2>*>(sim.get());
  REQUIRE(bsmpm != nullptr);
  const double k = kPi / kH, nu = kMu / kRho;
  Particles& ps = bsmpm->state().particles;
  for (std::size_t p = 0; p < ps.size(); ++p) ps.v[p] = Vec2(kU * std::cos(k * ps.x[p].y()), 0.0);
  test::step_through(*sim, scene, [](const Simulation&) {});
  const double decay = std::exp(-nu * k * k * sim->time());  // 1/e after t = 1 / (nu k^2) = 0.101 s

  // Amplitude of the mode, A = (2 / N) sum u_p cos(k y_p), and the profile averaged along x
  // in each row of particles (spacing H / 40), over the middle third of the tank.
  const int rows = 40;
  std::vector<double> row_sum(rows, 0.0);
  std::vector<int> row_count(rows, 0);
  double projection = 0.0;
  int n = 0;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const Vec2& x = sim->particles().x[p];
    const Vec2& v = sim->particles().v[p];
    if (x.x() < kL / 3 || x.x() > 2 * kL / 3) continue;
    projection += v.x() * std::cos(k * x.y());
    const int row = std::clamp(static_cast<int>(x.y() / kH * rows), 0, rows - 1);
    row_sum[row] += v.x() - kU * decay * std::cos(k * x.y());
    ++row_count[row];
    ++n;
  }
  REQUIRE(n > 1000);
  double worst = 0.0;
  for (int r = 0; r < rows; ++r) {
    REQUIRE(row_count[r] > 0);
    worst = std::max(worst, std::abs(row_sum[r] / row_count[r]));
  }
  const double amplitude = 2.0 * projection / n;
  INFO("t = " << sim->time() << " s: amplitude " << amplitude / kU << " U against exp(-nu k^2 t) = " << decay
              << "; largest deviation of the row-averaged profile " << worst / kU << " U");
  // (Inviscid, the amplitude would stay 2.7 times higher.)
  CHECK(std::abs(amplitude / (kU * decay) - 1.0) <= kAmplitudeBound);
  CHECK(worst <= kProfileBound * kU);
}

// The hard cases (tests/hard/scenes/), each at spline orders 1, 2 and 3 with the Courant
// number 0.8, near the largest stable one (1.0 made the piston at order 3, the spray at order
// 1 and the stiff gate at order 2 fail; see the beyond-the-limit cases below). Over the whole
// run every case must keep, with these bounds:
//  - finite fields, the mass exact, every particle inside the tank, the run finishing;
//  - rho/rho0 of the water in [0.6, 1.5] (the run stops outside [0.5, 2], the default
//    solver.density_range);
//  - no water deeper inside a solid than 0.5 cells;
//  - total energy <= start + work from outside (rigid pushes) + 1 % of the energy scale.
// Measured worst values (in the comments: order 1 / 2 / 3) were taken with hard_case_measure
// on this commit; the margins are the distance to the bound.
#include <catch2/catch.hpp>

#include "hard_case.hpp"

using namespace bsmpm;
using test::HardCaseReport;

namespace {

constexpr double kMinDensity = 0.6, kMaxDensity = 1.5;
constexpr double kMaxPenetrationCells = 0.5;
constexpr double kMaxEnergyExcess = 0.01;

void require_stable(const HardCaseReport& r) {
  INFO(test::describe(r));
  CHECK(r.finished);
  CHECK(r.finite);
  CHECK(r.mass_exact);
  CHECK(r.inside_tank);
  CHECK(r.min_density >= kMinDensity);
  CHECK(r.max_density <= kMaxDensity);
  CHECK(r.max_penetration <= kMaxPenetrationCells);
  CHECK(r.max_energy_excess <= kMaxEnergyExcess);
}

std::vector<std::string> near_limit(int order, std::vector<std::string> more = {}) {
  more.push_back("grid.order=" + std::to_string(order));
  more.push_back("time.cfl=0.8");
  return more;
}

}  // namespace

// rho/rho0 0.790-1.337 / 0.857-1.281 / 0.846-1.214; energy change -18 / -11 / -9 %, excess
// <= 0 (margin 1 % of 4254 J/m).
TEST_CASE("Hard case: a tall column (H = 1.2 m) slams into the wall", "[hard]") {
  const int order = GENERATE(1, 2, 3);
  INFO("order " << order);
  require_stable(test::run_hard_case("tall_column.toml", near_limit(order)));
}

// Soft (E = 1e5 Pa): rho/rho0 0.965-1.056 / 0.962-1.051 / 0.973-1.046, no penetration, excess
// <= 0. Stiff (E = 1e9 Pa, 630 m/s waves, 12,500 steps): 0.973-1.055 / 0.968-1.049 /
// 0.978-1.044, no penetration, excess <= 0.
TEST_CASE("Hard case: a very soft and a very stiff gate against the same water", "[hard]") {
  const int order = GENERATE(1, 2, 3);
  const std::string stiffness = GENERATE(as<std::string>{}, "1e5", "1e9");
  INFO("order " << order << ", E = " << stiffness);
  require_stable(
      test::run_hard_case("gate.toml", near_limit(order, {"materials.gate.youngs_modulus=" + stiffness})));
}

// Block: rho/rho0 0.929-1.199 / 0.923-1.123 / 0.906-1.140, penetration 0 cells, excess <= 0
// (the block puts in 0.8 of the scale). Piston (the corner case): 0.900-1.115 / 0.823-1.167 /
// 0.946-1.136, penetration 0.32 / 0.21 / 0.20 cells (margin 0.18), excess 0.0024 / <= 0 / <= 0.
TEST_CASE("Hard case: a rigid block enters the water at 5 m/s", "[hard]") {
  const int order = GENERATE(1, 2, 3);
  INFO("order " << order);
  require_stable(test::run_hard_case("block_drop.toml", near_limit(order)));
}

TEST_CASE("Hard case: a rigid piston drives water into a corner", "[hard]") {
  const int order = GENERATE(1, 2, 3);
  INFO("order " << order);
  require_stable(test::run_hard_case("piston_corner.toml", near_limit(order)));
}

// rho/rho0 0.959-1.051 / 0.981-1.041 / 0.966-1.090; penetration 0.25 / 0.20 / 0.21 cells (the
// gap is half a cell: water in it sits within the wall's B-spline support), excess <= 0.
TEST_CASE("Hard case: water drains through a gap narrower than one cell", "[hard]") {
  const int order = GENERATE(1, 2, 3);
  INFO("order " << order);
  require_stable(test::run_hard_case("narrow_gap.toml", near_limit(order)));
}

// Orders 2 and 3: rho/rho0 0.707-1.288 / 0.761-1.264, penetration 0, excess 0.0048 / <= 0.
TEST_CASE("Hard case: spray (lone particles, a thin jet) hits a wall and solids", "[hard]") {
  const int order = GENERATE(2, 3);
  INFO("order " << order);
  require_stable(test::run_hard_case("spray.toml", near_limit(order)));
}

// KNOWN INSTABILITY (reported with issue 12), its symptom pinned: at order 1 the lone
// particles gain energy, 0.70 of the scale at Courant 0.8, and a drop reaches 1.08 cells into
// the rigid block (rho/rho0 down to 0.597), measured with hard_case_measure. The run still
// finishes. Once fixed, this check fails: then the case joins the one above.
TEST_CASE("Hard case: spray at spline order 1 gains energy and enters the block (known)", "[hard][known]") {
  const HardCaseReport r = test::run_hard_case("spray.toml", near_limit(1));
  INFO(test::describe(r));
  CHECK(r.finished);
  CHECK(r.finite);
  CHECK(r.max_energy_excess > 0.5);                    // measured 0.70; the bound is 0.01
  CHECK(r.max_penetration > kMaxPenetrationCells);     // measured 1.076 cells; the bound is 0.5
}

// No drift, no creep: the water starts in hydrostatic equilibrium and must stay in it for
// 10 s. Measured without the volume smoothing, orders 1 / 2 (hard_case_measure): speed 0.0002
// / 0.00119 m/s, displacement 2.23e-6 / 5.17e-6 m (4.5e-5 / 1.03e-4 cells), energy change
// < 1e-4 of the scale. Bounds, about ten times the worst order's: speed < 0.01 m/s,
// displacement < 1e-3 cells, |energy change| < 1e-3 of the scale.
namespace {
void require_still(const HardCaseReport& r) {
  INFO(test::describe(r));
  require_stable(r);
  CHECK(r.max_speed < 0.01);
  CHECK(r.max_displacement < 1e-3 * r.cell);
  CHECK(std::abs(r.final_energy_change) < 1e-3);
}
}  // namespace

TEST_CASE("Hard case: a still tank stays still for 10 s", "[hard]") {
  const int order = GENERATE(1, 2);
  INFO("order " << order);
  require_still(test::run_hard_case("still_tank.toml", near_limit(order, {"solver.smooth_fluid_volume=false"})));
}

// KNOWN INSTABILITY (reported with issue 12), its symptom pinned: at order 3 the still tank
// starts to move: speed 1.34 m/s and displacement 0.56 m within 10 s (rho/rho0 0.956-1.043),
// measured with hard_case_measure; the bound of a still tank is 0.01 m/s. Once fixed, this
// check fails: then the case joins the one above.
TEST_CASE("Hard case: a still tank at spline order 3 starts to move (known)", "[hard][known]") {
  const HardCaseReport r =
      test::run_hard_case("still_tank.toml", near_limit(3, {"solver.smooth_fluid_volume=false"}));
  INFO(test::describe(r));
  CHECK(r.finished);
  CHECK(r.max_speed > 0.5);  // measured 1.34 m/s
}

// KNOWN INSTABILITY (reported with issue 12), its symptom pinned: with
// solver.smooth_fluid_volume (as the shipped water scenes run) the still tank starts to move
// at every order: within 10 s the fastest particle reaches 1.0 / 2.13 / 1.73 m/s at orders
// 1 / 2 / 3 (0.50-0.60 m displaced), measured with hard_case_measure; at order 2 it was
// 0.008 m/s at 1 s, 0.04 at 1.5 s, 0.12 at 2 s; a smaller step (Courant 0.2) does not help,
// a finer grid (2.5 cm) makes it worse. Once fixed, this check fails: then the case joins the
// still tanks above.
TEST_CASE("Hard case: a still tank with the fluid volume smoothing starts to move (known)", "[hard][known]") {
  const int order = GENERATE(1, 2, 3);
  INFO("order " << order);
  const HardCaseReport r = test::run_hard_case("still_tank.toml", near_limit(order));
  INFO(test::describe(r));
  CHECK(r.finished);
  CHECK(r.max_speed > 0.5);  // measured 1.0 m/s at least
}

// Beyond the largest stable step: a fixed step 1.5 and 3 times the acoustic limit h/(c + v)
// (run_cost.hpp). Measured at order 2 (hard_case_measure): x1.5 the block finishes stable;
// the column, piston, gap and spray stop with the diagnosis (density out of range, at steps
// 447, 36, 93, 199); x3 every case stops within 7 steps (at steps 3, 7, 4, 4, 6). Never
// silently: a case that stops names step, body and particle.
TEST_CASE("Hard cases beyond the largest stable time step stop with the diagnosis, the block at x1.5 stays stable",
          "[hard]") {
  const std::string scene = GENERATE(as<std::string>{}, "tall_column.toml", "block_drop.toml", "piston_corner.toml",
                                     "narrow_gap.toml", "spray.toml");
  const double factor = GENERATE(1.5, 3.0);
  INFO(scene << " at " << factor << " times the acoustic limit");
  const HardCaseReport r = test::run_hard_case(scene, {}, factor);
  INFO(test::describe(r));
  if (factor == 1.5 && scene == "block_drop.toml") {
    require_stable(r);
    return;
  }
  REQUIRE(!r.finished);
  CHECK(r.error.find("numerical instability at step ") != std::string::npos);
  CHECK(r.error.find("body '") != std::string::npos);
  CHECK(r.error.find("particle ") != std::string::npos);
  if (factor == 3.0) CHECK(r.steps < 7);  // the failing step is at most the 7th
}

// KNOWN SILENT FAILURE (reported with issue 12), its symptom pinned: the stiff gate at 1.5
// times the acoustic limit finishes with finite fields and densities in range, but gains
// energy: 0.177 of the scale above the start (hard_case_measure). Nothing stops it;
// conservation.csv shows it. Once the run stops or keeps its energy, this check fails.
TEST_CASE("Hard case: the stiff gate beyond the limit gains energy silently (known)", "[hard][known]") {
  const HardCaseReport r = test::run_hard_case("gate.toml", {"materials.gate.youngs_modulus=1e9"}, 1.5);
  INFO(test::describe(r));
  CHECK(r.finished);
  CHECK(r.finite);
  CHECK(r.max_energy_excess > 0.1);  // measured 0.177; the bound is 0.01
}

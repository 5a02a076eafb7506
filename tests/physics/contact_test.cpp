// The contact algorithm of Li, Lian et al. (2024) as used by Hua et al. (2025):
// colliding disks, no premature contact, Coulomb friction on an incline.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>

#include <cmath>

#include "physics/energy.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bounds of the colliding disks (R_a = 0.2, R_b = 0.15, h = 0.05, order 2,
// CFL 0.3 as the scene ships), measured on 2026-12-01:
// - restitution (separation over approach speed of the centres) 0.803; bound 0.78, a
//   margin for solver changes (at CFL 0.1 it is 0.755: the time step matters at this level);
// - kinetic energy after the disks parted 82.7-90.6 % of the energy before (it swaps with
//   the elastic energy of their vibration); floor 80 %;
// - kinetic plus elastic energy after parting +3.7 to +4.3 % of the energy before: the
//   explicit step's energy error at CFL 0.3 (at CFL 0.1: -2.3 %); bound 6 %.
constexpr double kDiskRestitutionAtLeast = 0.78;
constexpr double kDiskKineticKeptAtLeast = 0.80;
constexpr double kDiskEnergyChangeBound = 0.06;
// - the total momentum, round-off only: off by 5.8e-16 of the momentum scale (sum of |m v|)
//   in separate fields and 7.0e-16 in one (stick) after 350 steps; bound ten times that.
constexpr double kContactMomentumBound = 7e-15;
// - the block on an incline with tan a < mu: its shift after 0.5 s while it settles
//   elastically onto the floor, 1.9e-5 m; bound ten times that (frictionless, it would slide
//   0.21 m).
constexpr double kStaysPutBound = 2e-4;  // m

struct BodyMotion {
  Vec2 centre = Vec2::Zero(), velocity = Vec2::Zero();
  double mass = 0.0;
};

// The gap in x between the surfaces of body `behind` (its front, largest x) and of body
// `ahead` (its back, smallest x): their particles' distance less half of each one's spacing.
double gap_x(const Simulation& sim, int behind, int ahead) {
  const Particles& ps = sim.particles();
  const Body& a = sim.bodies()[behind];
  const Body& b = sim.bodies()[ahead];
  double front = -1e9, back = 1e9;
  for (std::size_t p = a.begin; p < a.end; ++p) front = std::max(front, ps.x[p].x());
  for (std::size_t p = b.begin; p < b.end; ++p) back = std::min(back, ps.x[p].x());
  return back - front - 0.5 * (a.spacing.x() + b.spacing.x());
}

BodyMotion motion(const Simulation& sim, int body) {
  const Particles& ps = sim.particles();
  const Body& b = sim.bodies()[body];
  BodyMotion m;
  for (std::size_t p = b.begin; p < b.end; ++p) {
    m.mass += ps.mass[p];
    m.centre += ps.mass[p] * ps.x[p];
    m.velocity += ps.mass[p] * ps.v[p];
  }
  m.centre /= m.mass;
  m.velocity /= m.mass;
  return m;
}

using test::kinetic_energy;
using test::momentum;

struct DiskRun {
  double closest = 1e9;          // smallest distance between the disk centres
  double closest_particles = 1e9;  // smallest distance between particles of different disks
  double gap_at_first_push = -1.0;  // gap between the particle clouds when the approach first slowed by 1 %
  double final_distance = 0.0;
  double approach_speed = 0.0;         // of the centres along their line, before contact
  double final_separation_speed = 0.0;  // the same after the rebound
  double kinetic_before = 0.0, kinetic_after = 0.0;
  double energy_before = 0.0;  // kinetic plus stored elastic energy
  // After the disks have parted (centres R_a + R_b + 2h apart): the range of the kinetic
  // energy (it swaps with the elastic energy of the disks' vibration) and of the total.
  double kinetic_low = 1e300, kinetic_high = 0.0, energy_low = 1e300, energy_high = 0.0;
  double momentum_drift = 0.0;   // largest |P(t) - P(0)| of the total momentum
  double momentum_scale = 0.0;   // sum of |m v| at the start
  int fields = 0;                // grid velocity fields of the scene
};

// scenes/colliding_disks.toml (Sulsky et al. 1994) with disk_b smaller than disk_a, so that
// the two are not mirror images of each other: a symmetric error in the contact law (equal
// velocity changes instead of equal and opposite impulses) then shows in the momentum.
DiskRun run_disks(const std::string& contact_type) {
  // Mass cut-off 0: no node is dropped, so momentum is conserved to round-off.
  const SceneDescription scene =
      load_scene(test::scene_path("colliding_disks.toml"),
                 {"contacts[0].type=" + contact_type, "solver.mass_cutoff=0", "bodies[1].shape.radius=0.15"});
  auto sim = build_simulation(scene);
  DiskRun r;
  r.fields = sim->layer_count();
  r.kinetic_before = kinetic_energy(*sim);
  r.energy_before = r.kinetic_before + test::stored_energy(*sim);
  const Vec2 momentum0 = momentum(*sim);
  for (std::size_t p = 0; p < sim->particles().size(); ++p)
    r.momentum_scale += sim->particles().mass[p] * sim->particles().v[p].norm();
  {
    const BodyMotion a = motion(*sim, 0), b = motion(*sim, 1);
    r.approach_speed = -(b.velocity - a.velocity).dot((b.centre - a.centre).normalized());
  }
  test::step_through(*sim, scene, [&](const Simulation& s) {
    const BodyMotion a = motion(s, 0), b = motion(s, 1);
    const double distance = (b.centre - a.centre).norm();
    r.closest = std::min(r.closest, distance);
    r.momentum_drift = std::max(r.momentum_drift, (momentum(s) - momentum0).norm());
    const Vec2 u = (b.centre - a.centre) / distance;
    const double approach = -(b.velocity - a.velocity).dot(u);
    const Particles& ps = s.particles();
    const Body& da = s.bodies()[0];
    const Body& db = s.bodies()[1];
    if (r.gap_at_first_push < 0.0 && approach < 0.99 * r.approach_speed) {
      // Gap along the line of centres between the two clouds of particle cells.
      double front_a = -1e9, back_b = 1e9;
      for (std::size_t p = da.begin; p < da.end; ++p) front_a = std::max(front_a, ps.x[p].dot(u));
      for (std::size_t q = db.begin; q < db.end; ++q) back_b = std::min(back_b, ps.x[q].dot(u));
      r.gap_at_first_push = back_b - front_a - (std::abs(u.x()) + std::abs(u.y())) * da.spacing.x();
    }
    if (distance > 0.45 && approach < 0.0) {  // parted: R_a + R_b + 2h
      const double kinetic = kinetic_energy(s), total = kinetic + test::stored_energy(s);
      r.kinetic_low = std::min(r.kinetic_low, kinetic);
      r.kinetic_high = std::max(r.kinetic_high, kinetic);
      r.energy_low = std::min(r.energy_low, total);
      r.energy_high = std::max(r.energy_high, total);
    }
    if (distance < 0.45)  // within 0.1 m of touching (R_a + R_b = 0.35)
      for (std::size_t p = da.begin; p < da.end; ++p)
        for (std::size_t q = db.begin; q < db.end; ++q) r.closest_particles = std::min(r.closest_particles, (ps.x[p] - ps.x[q]).norm());
  });
  const BodyMotion a = motion(*sim, 0), b = motion(*sim, 1);
  const Vec2 axis = (b.centre - a.centre).normalized();
  r.final_distance = (b.centre - a.centre).norm();
  r.final_separation_speed = (b.velocity - a.velocity).dot(axis);
  r.kinetic_after = kinetic_energy(*sim);
  return r;
}

}  // namespace

TEST_CASE("Colliding disks bounce apart with contact, momentum kept and energy accounted for", "[physics][contact]") {
  // Radii R_a = 0.2, R_b = 0.15 (mass ratio 0.56), h = 0.05, closing at 0.283 m/s.
  const double Ra = 0.2, Rb = 0.15, h = 0.05;
  const DiskRun r = run_disks("frictionless");
  const double spacing = h / 2;
  const double restitution = r.final_separation_speed / r.approach_speed;
  INFO("closest centres " << r.closest << ", closest particles " << r.closest_particles << ", first push at gap "
                          << r.gap_at_first_push << ", final distance " << r.final_distance << ", separating at "
                          << r.final_separation_speed << " m/s (restitution " << restitution << "), KE "
                          << r.kinetic_after << " / " << r.kinetic_before << " (after parting " << r.kinetic_low
                          << " .. " << r.kinetic_high << "), kinetic + elastic " << r.energy_low << " .. "
                          << r.energy_high << " / " << r.energy_before << ", momentum drift " << r.momentum_drift
                          << " of " << r.momentum_scale);
  REQUIRE(r.fields == 2);  // one velocity field per disk
  // The disks push each other only once their particle cells touch (gap below h/10) ...
  CHECK(r.gap_at_first_push < 0.1 * h);
  CHECK(r.closest < Ra + Rb);  // (they flatten against each other: E is only 1 kPa)
  // ... and do not run into each other: particles of the two disks stay half a spacing apart.
  CHECK(r.closest_particles > 0.5 * spacing);
  CHECK(r.final_distance > Ra + Rb + 2 * h);
  // Momentum: the contact impulses cancel pairwise; 350 steps of round-off.
  CHECK(r.momentum_drift <= kContactMomentumBound * r.momentum_scale);
  // Restitution and energy after the rebound. Elastic disks conserve their kinetic plus
  // elastic energy and cannot part faster than they met (e <= 1); part of the energy stays in
  // their vibration, more the faster the impact is against the wave speed (Gerl & Zippelius
  // 1999, Phys. Rev. E 59:2361; here 0.283 m/s against c = 1.16 m/s), so e < 1 and the
  // kinetic energy alone falls. Measured values and bounds: see kDiskRestitutionAtLeast.
  CHECK(restitution <= 1.0);
  CHECK(restitution >= kDiskRestitutionAtLeast);
  CHECK(r.kinetic_high <= r.kinetic_before);
  CHECK(r.kinetic_low >= kDiskKineticKeptAtLeast * r.kinetic_before);
  CHECK(std::abs(r.energy_low - r.energy_before) <= kDiskEnergyChangeBound * r.energy_before);
  CHECK(std::abs(r.energy_high - r.energy_before) <= kDiskEnergyChangeBound * r.energy_before);
}

TEST_CASE("Disks in a single field (stick) share one velocity field and interact before touching",
          "[physics][contact]") {
  // "stick" between two deformable bodies merges their fields: standard MPM. As in Sulsky
  // et al. (1994) the disks rebound; but with one field they start pushing each other through
  // the shared control points while their surfaces are still about a cell apart (measured
  // 0.93 h for equal disks), the premature contact that the distance criterion removes.
  const double h = 0.05;
  const DiskRun single = run_disks("stick");
  INFO("first push at a surface gap of " << single.gap_at_first_push << " m; momentum drift "
                                           << single.momentum_drift / single.momentum_scale << " of the scale");
  CHECK(single.fields == 1);  // merged: what makes this a single field, not a contact law
  CHECK(single.gap_at_first_push > 0.5 * h);
  CHECK(single.momentum_drift <= kContactMomentumBound * single.momentum_scale);
}

namespace {

// Gap between the blocks' surfaces (particle centres are half a spacing inside them), and
// the largest gap at which a contact force acted.
double largest_gap_with_force(int order, bool distance_check, double* closest_gap = nullptr) {
  const SceneDescription scene =
      load_scene(test::scene_path("approaching_blocks.toml"),
                 {"grid.order=" + std::to_string(order), std::string("contacts[0].distance_check=") +
                                                             (distance_check ? "true" : "false")});
  auto sim = build_simulation(scene);
  double largest = -1.0, smallest = 1e9;
  test::step_through(*sim, scene, [&](const Simulation& s) {
    const double gap = gap_x(s, 0, 1);
    smallest = std::min(smallest, gap);
    if (s.last_step().contact_impulse > 0.0) largest = std::max(largest, gap);
  });
  if (closest_gap) *closest_gap = smallest;
  return largest;
}

}  // namespace

TEST_CASE("No premature contact: no force while the gap exceeds h/10 (orders 2 and 3)", "[physics][contact]") {
  // scenes/approaching_blocks.toml: h = 10 mm, initial gap 30 mm, closing at 1 m/s.
  const double h = 0.01;
  for (int order : {2, 3}) {
    double closest = 0.0;
    const double with_check = largest_gap_with_force(order, true, &closest);
    const double without_check = largest_gap_with_force(order, false);
    INFO("order " << order << ": largest gap with a contact force " << with_check << " m with the distance "
                  << "criterion, " << without_check << " m without; closest gap " << closest);
    REQUIRE(with_check > -1.0);  // they did come into contact
    CHECK(with_check <= 0.1 * h);
    CHECK(closest > -0.25 * h);  // and the contact held
    // Without the distance criterion the blocks push each other while more than a cell apart.
    CHECK(without_check > 1.0 * h);
  }
}

namespace {
// Displacement along the incline of the block's corner, sampled at every probe row.
std::vector<std::pair<double, double>> slide(double slope_deg) {
  const auto run = test::run_scene("incline_block.toml", {"gravity.slope_deg=" + std::to_string(slope_deg)});
  const Probe* corner = test::find_probe(*run.sim, "corner");
  REQUIRE(corner != nullptr);
  std::vector<std::pair<double, double>> out;
  for (std::size_t r = 0; r < corner->row_count(); ++r) out.emplace_back(corner->row(r)[0], corner->row(r)[1]);
  return out;
}
}  // namespace

TEST_CASE("A block slides down a rigid incline at g (sin a - mu cos a) and sticks when tan a < mu",
          "[physics][contact]") {
  const double g = 9.81, mu = 0.3;
  SECTION("tan a > mu: slides") {
    const double a = 30.0 * kPi / 180.0;
    const double expected = g * (std::sin(a) - mu * std::cos(a));
    // Least-squares fit x = x0 + v0 t + acc t^2 / 2 over t in [0.1, 0.5] s, after the block
    // has settled onto the floor.
    double s[5] = {0, 0, 0, 0, 0}, sx[3] = {0, 0, 0};
    for (const auto& [t, x] : slide(30.0)) {
      if (t < 0.1) continue;
      double tp = 1.0;
      for (int k = 0; k < 5; ++k, tp *= t) s[k] += tp;
      sx[0] += x;
      sx[1] += x * t;
      sx[2] += x * t * t;
    }
    Eigen::Matrix3d A;
    A << s[0], s[1], s[2], s[1], s[2], s[3], s[2], s[3], s[4];
    const Eigen::Vector3d c = A.ldlt().solve(Eigen::Vector3d(sx[0], sx[1], sx[2]));
    const double acceleration = 2.0 * c[2];
    INFO("acceleration " << acceleration << " m/s2 against " << expected);
    // Measured on 2026-12-03 (h = 10 mm, order 2): 2.35559 m/s2 against 2.35629 (-0.03 %).
    // Bound 0.3 %, ten times that: a friction coefficient off by 0.3 % (0.001) moves the
    // acceleration by 0.33 %.
    CHECK(acceleration == Approx(expected).epsilon(0.003));
  }
  SECTION("tan a < mu: stays put") {
    const auto path = slide(10.0);
    // Frictionless, it would slide g sin(10 deg) t^2 / 2 = 0.21 m in 0.5 s (kStaysPutBound).
    INFO("shift " << path.back().second << " m");
    CHECK(std::abs(path.back().second) < kStaysPutBound);
  }
}

TEST_CASE("A rigid body moving at a prescribed velocity pushes an elastic block ahead of it",
          "[physics][contact]") {
  // A rigid piston at 0.5 m/s, 30 mm behind an elastic block at rest; no gravity.
  const SceneDescription scene = load_scene(test::fixture_path("piston_block.toml"));
  auto sim = build_simulation(scene);
  double deepest = 1e9;  // smallest gap between the piston's front face and the block
  test::step_through(*sim, scene, [&](const Simulation& s) {
    deepest = std::min(deepest, gap_x(s, 0, 1));
    const Particles& ps = s.particles();
    const Body& piston = s.bodies()[0];
    for (std::size_t p = piston.begin; p < piston.end; ++p) REQUIRE(ps.v[p] == Vec2(0.5, 0.0));
  });
  const BodyMotion block = motion(*sim, 1);
  const double V = 0.5, restitution = (block.velocity.x() - V) / V;  // in the piston's frame
  INFO("block velocity " << block.velocity.transpose() << " (restitution " << restitution << "), smallest gap "
                         << deepest);
  // Hit by an infinitely heavy wall at V, an elastic bar leaves at exactly 2V: the
  // compression wave reflects from its free end as a release wave, which leaves it stress-free
  // at 2V (restitution 1 in the wall's frame). The block is no bar (0.12 x 0.1 m, plane
  // strain, nu = 0.3): part of the impact stays in its vibration, as with the disks. Measured
  // on 2026-12-01 (h = 10 mm, order 2): 0.894 m/s, restitution 0.788; bound 0.75 (a margin
  // of 0.04, as the disks' restitution moves by 0.05 with the time step).
  CHECK(restitution <= 1.0);
  CHECK(restitution >= 0.75);
  CHECK(std::abs(block.velocity.y()) < 1e-9);  // the set-up is symmetric about y = 0.2 m
  CHECK(deepest > -0.25 * 0.01);  // never more than a quarter cell into the piston
}

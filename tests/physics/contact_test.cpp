// The contact algorithm of Li, Lian et al. (2024) as used by Hua et al. (2025):
// colliding disks, no premature contact, Coulomb friction on an incline.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>

#include <cmath>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

struct BodyMotion {
  Vec2 centre = Vec2::Zero(), velocity = Vec2::Zero();
  double mass = 0.0;
};

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

double kinetic_energy(const Simulation& sim) {
  const Particles& ps = sim.particles();
  double e = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) e += 0.5 * ps.mass[p] * ps.v[p].squaredNorm();
  return e;
}

Vec2 momentum(const Simulation& sim) {
  const Particles& ps = sim.particles();
  Vec2 m = Vec2::Zero();
  for (std::size_t p = 0; p < ps.size(); ++p) m += ps.mass[p] * ps.v[p];
  return m;
}

struct DiskRun {
  double closest = 1e9;          // smallest distance between the disk centres
  double closest_particles = 1e9;  // smallest distance between particles of different disks
  double gap_at_first_push = -1.0;  // gap between the particle clouds when the approach first slowed by 1 %
  double final_distance = 0.0;
  double final_separation_speed = 0.0;
  double kinetic_before = 0.0, kinetic_after = 0.0;
  double momentum_drift = 0.0;   // largest |total momentum| seen (it starts at zero)
  double momentum_scale = 0.0;   // sum of |m v| at the start
};

DiskRun run_disks(const std::string& contact_type) {
  // Mass cut-off 0: no node is dropped, so momentum is conserved to round-off.
  const SceneDescription scene = load_scene(test::scene_path("colliding_disks.toml"),
                                            {"contacts[0].type=" + contact_type, "solver.mass_cutoff=0"});
  auto sim = build_simulation(scene);
  DiskRun r;
  r.kinetic_before = kinetic_energy(*sim);
  for (std::size_t p = 0; p < sim->particles().size(); ++p)
    r.momentum_scale += sim->particles().mass[p] * sim->particles().v[p].norm();
  const double approach0 = 0.2 * std::sqrt(2.0);
  test::step_through(*sim, scene, [&](const Simulation& s) {
    const BodyMotion a = motion(s, 0), b = motion(s, 1);
    const double distance = (b.centre - a.centre).norm();
    r.closest = std::min(r.closest, distance);
    r.momentum_drift = std::max(r.momentum_drift, momentum(s).norm());
    const Vec2 u = (b.centre - a.centre) / distance;
    const double approach = -(b.velocity - a.velocity).dot(u);
    const Particles& ps = s.particles();
    const Body& da = s.bodies()[0];
    const Body& db = s.bodies()[1];
    if (r.gap_at_first_push < 0.0 && approach < 0.99 * approach0) {
      // Gap along the line of centres between the two clouds of particle cells.
      double front_a = -1e9, back_b = 1e9;
      for (std::size_t p = da.begin; p < da.end; ++p) front_a = std::max(front_a, ps.x[p].dot(u));
      for (std::size_t q = db.begin; q < db.end; ++q) back_b = std::min(back_b, ps.x[q].dot(u));
      r.gap_at_first_push = back_b - front_a - (std::abs(u.x()) + std::abs(u.y())) * da.spacing.x();
    }
    if (distance < 0.5)  // within 0.1 m of touching (2R = 0.4)
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

TEST_CASE("Colliding disks bounce apart with contact; momentum and energy", "[physics][contact]") {
  // scenes/colliding_disks.toml: radius R = 0.2, h = 0.05, closing speed 0.283 m/s.
  const double R = 0.2, h = 0.05;
  const DiskRun r = run_disks("frictionless");
  const double spacing = h / 2;
  INFO("closest centres " << r.closest << ", closest particles " << r.closest_particles << ", first push at gap "
                          << r.gap_at_first_push << ", final distance " << r.final_distance << ", separating at "
                          << r.final_separation_speed << " m/s, KE " << r.kinetic_after << " / " << r.kinetic_before);
  // The disks push each other only once their particle cells touch (gap below h/10) ...
  CHECK(r.gap_at_first_push < 0.1 * h);
  CHECK(r.closest < 2 * R);  // (they flatten against each other: E is only 1 kPa)
  // ... and do not run into each other: particles of the two disks stay half a spacing apart.
  CHECK(r.closest_particles > 0.5 * spacing);
  // They bounce apart and separate.
  CHECK(r.final_separation_speed > 0.0);
  CHECK(r.final_distance > 2 * R + 2 * h);
  // Momentum: the contact impulses cancel pairwise; 350 steps of round-off.
  CHECK(r.momentum_drift <= 1e-12 * r.momentum_scale);
  // Kinetic energy after the rebound (translation plus the disks' remaining vibration): no
  // energy is created, and at most 25 % goes to vibration and numerical dissipation
  // (measured: 85-92 %, oscillating with the vibration).
  CHECK(r.kinetic_after <= r.kinetic_before * (1.0 + 1e-9));
  CHECK(r.kinetic_after >= 0.75 * r.kinetic_before);
}

TEST_CASE("Disks in a single field (stick) interact through the shared field before touching",
          "[physics][contact]") {
  // "stick" puts both disks in one velocity field, i.e. standard MPM. As in Sulsky et al.
  // (1994) the disks rebound; but with one field they start pushing each other through the
  // shared control points while their surfaces are still about a cell apart (measured
  // 0.93 h), the premature contact that the distance criterion removes (0.03 h with it).
  const double h = 0.05;
  const DiskRun single = run_disks("stick");
  INFO("first push at a surface gap of " << single.gap_at_first_push << " m");
  CHECK(single.gap_at_first_push > 0.5 * h);
  CHECK(single.momentum_drift <= 1e-12 * single.momentum_scale);
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
    const Particles& ps = s.particles();
    const Body& left = s.bodies()[0];
    const Body& right = s.bodies()[1];
    double left_front = -1e9, right_back = 1e9;
    for (std::size_t p = left.begin; p < left.end; ++p) left_front = std::max(left_front, ps.x[p].x());
    for (std::size_t p = right.begin; p < right.end; ++p) right_back = std::min(right_back, ps.x[p].x());
    const double gap = right_back - left_front - 0.5 * (left.spacing.x() + right.spacing.x());
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
    CHECK(acceleration == Approx(expected).epsilon(0.05));  // the issue's 5 %
  }
  SECTION("tan a < mu: stays put") {
    const auto path = slide(10.0);
    // Frictionless, it would slide g sin(10 deg) t^2 / 2 = 0.21 m in 0.5 s; 1 mm is what the
    // block may shift while settling elastically onto the floor.
    CHECK(std::abs(path.back().second) < 1e-3);
  }
}

TEST_CASE("A rigid body moving at a prescribed velocity pushes an elastic block ahead of it",
          "[physics][contact]") {
  // A rigid piston at 0.5 m/s, 30 mm behind an elastic block at rest; no gravity.
  const std::string text = R"(
[domain]
min = [0.0, 0.0]
max = [1.0, 0.4]
[grid]
cell_size = 0.01
[time]
end = 0.2
cfl = 0.3
[gravity]
g = 0.0
[materials.steel]
type = "rigid"
velocity = [0.5, 0.0]
[materials.rubber]
type = "elastic"
density = 1000.0
youngs_modulus = 1.0e5
poisson_ratio = 0.3
[[bodies]]
name = "piston"
material = "steel"
shape = { type = "rectangle", min = [0.2, 0.1], max = [0.3, 0.3] }
[[bodies]]
name = "block"
material = "rubber"
shape = { type = "rectangle", min = [0.33, 0.15], max = [0.45, 0.25] }
[[contacts]]
bodies = ["piston", "block"]
type = "frictionless"
)";
  const SceneDescription scene = load_scene_text(text, "piston.toml");
  auto sim = build_simulation(scene);
  double deepest = 1e9;  // smallest gap between the piston's front face and the block
  test::step_through(*sim, scene, [&](const Simulation& s) {
    const Particles& ps = s.particles();
    const Body& piston = s.bodies()[0];
    const Body& block = s.bodies()[1];
    double front = -1e9, back = 1e9;
    for (std::size_t p = piston.begin; p < piston.end; ++p) front = std::max(front, ps.x[p].x());
    for (std::size_t p = block.begin; p < block.end; ++p) back = std::min(back, ps.x[p].x());
    deepest = std::min(deepest, back - front - 0.5 * (piston.spacing.x() + block.spacing.x()));
    for (std::size_t p = piston.begin; p < piston.end; ++p) REQUIRE(ps.v[p] == Vec2(0.5, 0.0));
  });
  const BodyMotion block = motion(*sim, 1);
  INFO("block velocity " << block.velocity.transpose() << ", smallest gap " << deepest);
  // Hit by an infinitely heavy wall at V = 0.5 m/s, the block leaves at least as fast as the
  // wall (it was pushed) and at most at 2V, the perfectly elastic rebound off a moving wall;
  // the 2 % margin covers the block's residual vibration in its mean velocity (measured 0.89 m/s).
  CHECK(block.velocity.x() > 0.5);
  CHECK(block.velocity.x() < 2.0 * 0.5 * 1.02);
  CHECK(std::abs(block.velocity.y()) < 0.01);
  CHECK(deepest > -0.25 * 0.01);  // never more than a quarter cell into the piston
}

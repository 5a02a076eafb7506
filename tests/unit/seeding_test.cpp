// Shapes and the particles seeded in them.
#include <catch2/catch.hpp>

#include "particles/seeding.hpp"

using namespace bsmpm;

namespace {
double total(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}
}  // namespace

TEST_CASE("Rectangles are filled exactly", "[seeding]") {
  // 0.61 / 0.004 = 152.5 columns: rounded to 152 (or 153) equal columns, volumes add up.
  const Rectangle r{Vec2(0.1, 0.0), Vec2(0.71, 0.3)};
  const SeededPoints pts = seed_particles(r, Vec2::Zero(), Vec2(0.004, 0.004));
  CHECK(total(pts.volumes) == Approx(0.61 * 0.3).epsilon(1e-12));
  for (const Vec2& x : pts.positions) CHECK(contains(Shape(r), x));
  CHECK(pts.spacing.x() == Approx(0.61 / std::lround(0.61 / 0.004)));
}

TEST_CASE("Disks and polygons take the lattice points inside them", "[seeding]") {
  const double d = 0.002;
  SECTION("disk") {
    const Disk disk{Vec2(0.5, 0.4), 0.1};
    const SeededPoints pts = seed_particles(disk, Vec2::Zero(), Vec2(d, d));
    for (const Vec2& x : pts.positions) CHECK((x - disk.center).norm() <= disk.radius);
    // The lattice cells cover the disk to within its perimeter times a cell.
    CHECK(total(pts.volumes) == Approx(area(disk)).margin(2 * kPi * 0.1 * d));
  }
  SECTION("concave polygon (an L)") {
    const Polygon ell{{Vec2(0, 0), Vec2(0.2, 0), Vec2(0.2, 0.05), Vec2(0.05, 0.05), Vec2(0.05, 0.2), Vec2(0, 0.2)}};
    CHECK(area(ell) == Approx(0.2 * 0.05 + 0.05 * 0.15));
    CHECK(contains(Shape(ell), Vec2(0.025, 0.15)));
    CHECK_FALSE(contains(Shape(ell), Vec2(0.15, 0.15)));  // the notch
    const SeededPoints pts = seed_particles(ell, Vec2::Zero(), Vec2(d, d));
    for (const Vec2& x : pts.positions) CHECK(contains(Shape(ell), x));
    // This polygon's edges lie on lattice lines: the cells tile it exactly.
    CHECK(total(pts.volumes) == Approx(area(ell)).epsilon(1e-9));
  }
  SECTION("triangle, either orientation") {
    const Polygon ccw{{Vec2(0, 0), Vec2(0.3, 0), Vec2(0, 0.1)}};
    const Polygon cw{{Vec2(0, 0), Vec2(0, 0.1), Vec2(0.3, 0)}};
    CHECK(area(ccw) == Approx(0.015));
    CHECK(area(cw) == Approx(0.015));
    const SeededPoints a = seed_particles(ccw, Vec2::Zero(), Vec2(d, d));
    const SeededPoints b = seed_particles(cw, Vec2::Zero(), Vec2(d, d));
    // Lattice points exactly on the hypotenuse may fall either way with the vertex order.
    CHECK(std::abs(double(a.positions.size()) - double(b.positions.size())) <= 0.3 / d);
    CHECK(total(a.volumes) == Approx(0.015).margin(0.5 * (0.3 + 0.1 + 0.32) * d));
  }
}

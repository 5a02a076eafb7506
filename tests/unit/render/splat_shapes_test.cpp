// The splat shapes without GL: the neighbour search against brute force, the shape of a
// lone particle, of a particle inside and at the edge of a block, and independence of the
// thread count.
#include <catch2/catch.hpp>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "paint/neighbour_grid.hpp"
#include "paint/splat_shapes.hpp"

using namespace bsmpm;
using namespace bsmpm::render;

namespace {

std::vector<Vec2> random_cloud(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> points(n);
  for (Vec2& p : points) p = Vec2(u(rng), 0.5 * u(rng));
  return points;
}

// A block of nx x ny particles at the centres of cells of side h from the origin.
std::vector<Vec2> block(int nx, int ny, double h) {
  std::vector<Vec2> points;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) points.emplace_back((i + 0.5) * h, (j + 0.5) * h);
  return points;
}

std::size_t index_of(const std::vector<Vec2>& points, Vec2 p) {
  for (std::size_t k = 0; k < points.size(); ++k)
    if ((points[k] - p).norm() < 1e-12) return k;
  FAIL("no such point");
  return 0;
}

// The support of a splat along world direction v (unit), which must be one of its eight.
double support_along(const SplatShape& s, Vec2 v) {
  const double axis = std::atan2(s.axis_y, s.axis_x);
  for (int k = 0; k < 8; ++k) {
    const double a = axis + k * kPi / 4.0;
    if (Vec2(std::cos(a), std::sin(a)).dot(v) > 1.0 - 1e-9) return s.support[k];
  }
  FAIL("v is none of the splat's directions");
  return 0.0;
}

}  // namespace

TEST_CASE("The neighbour grid finds exactly the points within the radius", "[render][splat]") {
  const std::vector<Vec2> points = random_cloud(3000, 7);
  const double cell = 0.013;
  const NeighbourGrid grid(points, cell);
  for (const double r : {0.01, 0.03, 0.055}) {
    for (std::size_t i = 0; i < points.size(); i += 97) {
      std::set<std::size_t> found, rings, expected;
      grid.for_each_neighbour(i, r, [&](std::size_t j, const Vec2& d) {
        CHECK((points[i] + d - points[j]).norm() < 1e-15);
        found.insert(j);
      });
      for (int ring = 0; ring <= static_cast<int>(std::ceil(r / grid.cell())); ++ring)
        grid.for_each_in_ring(points[i], ring, r, i, [&](std::size_t j, const Vec2&) { CHECK(rings.insert(j).second); });
      for (std::size_t j = 0; j < points.size(); ++j)
        if (j != i && (points[j] - points[i]).norm() < r) expected.insert(j);
      CHECK(found == expected);
      CHECK(rings == expected);
    }
  }
  // Cell order visits every point once.
  std::vector<std::uint32_t> order = grid.cell_order();
  std::sort(order.begin(), order.end());
  CHECK(order.size() == points.size());
  CHECK(std::adjacent_find(order.begin(), order.end()) == order.end());
}

TEST_CASE("A lone particle's splat is its margin all round", "[render][splat]") {
  std::vector<SplatShape> shapes;
  compute_splat_shapes({Vec2(0.3, 0.2)}, {0.01}, 1.5, {}, shapes);
  REQUIRE(shapes.size() == 1);
  for (float h : shapes[0].support) CHECK(h == Approx(0.0075).epsilon(1e-5));
  CHECK(shapes[0].reach == Approx(0.0075 / std::cos(kPi / 8.0)).epsilon(1e-5));
}

TEST_CASE("A splat covers its Voronoi cell inside a block and stops half a spacing out at its edges",
          "[render][splat]") {
  const double h = 0.01;
  const std::vector<Vec2> points = block(20, 12, h);
  std::vector<SplatShape> shapes;
  compute_splat_shapes(points, std::vector<double>(points.size(), h), 1.0, {}, shapes);

  // Inside: no support cuts within the reach, which covers the cell (a square of side h)
  // and little more.
  const SplatShape& inner = shapes[index_of(points, Vec2(10.5 * h, 6.5 * h))];
  CHECK(inner.reach >= 0.5 * std::sqrt(2.0) * h * 0.999);
  CHECK(inner.reach <= 1.1 * h);
  for (float support : inner.support) CHECK(support >= inner.reach);

  // At the top edge: outward, half a spacing; along the edge and inward, no cut within
  // the reach.
  const SplatShape& top = shapes[index_of(points, Vec2(10.5 * h, 11.5 * h))];
  CHECK(support_along(top, Vec2(0.0, 1.0)) == Approx(0.5 * h).epsilon(1e-5));
  CHECK(support_along(top, Vec2(1.0, 0.0)) >= top.reach);
  CHECK(support_along(top, Vec2(-1.0, 0.0)) >= top.reach);
  CHECK(support_along(top, Vec2(0.0, -1.0)) >= top.reach);
  // At a corner: half a spacing out along both edges' normals (its axes lie along the
  // diagonals, so the normals are among its directions), and less along the diagonal.
  const SplatShape& corner = shapes[index_of(points, Vec2(19.5 * h, 11.5 * h))];
  CHECK(support_along(corner, Vec2(1.0, 0.0)) == Approx(0.5 * h).epsilon(1e-5));
  CHECK(support_along(corner, Vec2(0.0, 1.0)) == Approx(0.5 * h).epsilon(1e-5));
  CHECK(support_along(corner, Vec2(1.0, 1.0).normalized()) == Approx(0.5 * h).epsilon(1e-5));
}

TEST_CASE("Splat shapes do not depend on the number of threads", "[render][splat]") {
  // Enough particles for the parallel loop; a cloud with gaps, surfaces and dense spots.
  const std::vector<Vec2> points = random_cloud(20000, 11);
  const std::vector<double> side(points.size(), 0.004);
  const WorldRect walls{Vec2(0.0, 0.0), Vec2(1.0, 0.5)};
  const std::vector<Vec2> obstacle = random_cloud(500, 12);
  std::vector<SplatShape> one, two;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  compute_splat_shapes(points, side, 1.0, SplatObstacles{&walls, &obstacle}, one);
  omp_set_num_threads(2);
  compute_splat_shapes(points, side, 1.0, SplatObstacles{&walls, &obstacle}, two);
  omp_set_num_threads(threads);
  REQUIRE(one.size() == two.size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < one.size(); ++k)
    differing += one[k].reach != two[k].reach || one[k].support != two[k].support || one[k].axis_x != two[k].axis_x;
  CHECK(differing == 0);
}

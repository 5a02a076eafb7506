// The sub-cell volume fraction of particle shifting (docs/method.md §10, sub-cell shifting;
// sim/step/passes/subcell_volume.hpp): an even lattice drifts nowhere, walls included, and
// particles bunched into columns at the knots, which the grid's B-splines do not see, are
// pushed apart.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "step/passes/particle_shifting.hpp"

using namespace bsmpm;

namespace {

constexpr int kCellsX = 12, kCellsY = 10;
constexpr double kH = 0.01;

struct Lattice {
  std::vector<Vec2> x;
  double volume = 0.0;  // each particle's
};

// Two particles a cell and axis, at (k + 1/4) h and (k + 3/4) h; `toward_knot` in [0, 1) moves
// each x towards its nearest knot by that fraction of the distance (0: the even seeding).
Lattice seeded(double toward_knot) {
  Lattice l;
  const double s = kH / 2.0;
  l.volume = s * s;
  for (int i = 0; i < 2 * kCellsX; ++i)
    for (int j = 0; j < 2 * kCellsY; ++j) {
      double x = (i + 0.5) * s;
      const double knot = std::round(x / kH) * kH;
      x = knot + (1.0 - toward_knot) * (x - knot);
      l.x.emplace_back(x, (j + 0.5) * s);
    }
  return l;
}

ParticleWeights<2> weights_at(const Grid<2>& grid, const Vec2& x) {
  ParticleWeights<2> w;
  w.i0 = grid.bx.evaluate(x.x(), w.wx, w.gx);
  w.j0 = grid.by.evaluate(x.y(), w.wy, w.gy);
  return w;
}

// The grid's volumes sum_p S_Ip V_p (what particle-to-grid scatters with shifting on).
std::vector<double> grid_volumes(const Grid<2>& grid, const Lattice& l) {
  std::vector<double> V(grid.node_count(), 0.0);
  for (const Vec2& x : l.x) {
    const auto w = weights_at(grid, x);
    for (int a = 0; a <= 2; ++a)
      for (int c = 0; c <= 2; ++c) V[grid.index(w.i0 + a, w.j0 + c)] += w.wx[a] * w.wy[c] * l.volume;
  }
  return V;
}

}  // namespace

TEST_CASE("Sub-cell volume: the seeding lattice reads phi = 1 and drifts nowhere, walls included",
          "[shifting][unit]") {
  const Grid<2> grid(Vec2::Zero(), Vec2(kH, kH), kCellsX, kCellsY);
  const Lattice l = seeded(0.0);
  SubcellVolume<2> field(grid, Vec2(kH / 2, kH / 2));
  for (const Vec2& x : l.x) field.add(x, l.volume);
  // Round-off: measured 7e-14 per metre (phi's differences of O(1) sums over 5 mm); bound 1e-12.
  double largest = 0.0;
  for (const Vec2& x : l.x) largest = std::max(largest, field.gradient(x).norm());
  CHECK(largest < 1e-12);
}

TEST_CASE("Sub-cell volume: columns bunched at the knots, which the grid's splines do not see, are pushed apart",
          "[shifting][unit]") {
  const Grid<2> grid(Vec2::Zero(), Vec2(kH, kH), kCellsX, kCellsY);
  const Lattice l = seeded(0.6);  // columns at knot +- 0.1 h (the 2 mm tank behind the break: 1.3 / 0.65)
  const std::vector<double> V = grid_volumes(grid, l);
  // The grid's drift with D = 1 against the sub-cell drift with D_s = 1.
  const ParticleShifting<2> coarse(grid, Vec2(kH / 2, kH / 2), 1.0);
  SubcellVolume<2> field(grid, Vec2(kH / 2, kH / 2));
  for (const Vec2& x : l.x) field.add(x, l.volume);
  double coarse_largest = 0.0, fine_smallest = 1e300;
  int apart = 0, inside = 0;
  for (const Vec2& x : l.x) {
    // Away from the walls' cells (the lattice's normalisation, not the bunching, acts there).
    if (x.x() < 2 * kH || x.x() > (kCellsX - 2) * kH || x.y() < 2 * kH || x.y() > (kCellsY - 2) * kH) continue;
    ++inside;
    coarse_largest = std::max(coarse_largest, std::abs(coarse.shift(weights_at(grid, x), V, grid.ny(), x, 0).x()));
    const Vec2 drift = -(kH / 2) * (kH / 2) * field.gradient(x);  // -D_s s^2 grad phi_s
    fine_smallest = std::min(fine_smallest, std::abs(drift.x()));
    const double knot = std::round(x.x() / kH) * kH;
    if ((x.x() - knot) * drift.x() > 0.0) ++apart;  // away from its knot
  }
  REQUIRE(inside > 100);
  CHECK(apart == inside);
  // Measured: the grid's drift 1.6e-15 h at most (blind: a pattern that repeats from cell to
  // cell is a sum of h-periodic lattices, each of which the splines' partition of unity fills
  // evenly), the sub-cell drift 0.60 h at least; bounds: round-off, and half the measured.
  CHECK(coarse_largest < 1e-12 * kH);
  CHECK(fine_smallest > 0.3 * kH);
}

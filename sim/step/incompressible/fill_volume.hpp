// The incompressible fluid's volume measured by the particles' packing (docs/method.md §12,
// "What J measures", eq. I5; solver.pressure.volume_measure = "fill"): each step, before eq. I2,
//
//   fill_K = sum_p V0_p Q_K(x_p),   r_K = int Q_K / fill_K,   J_p = sum_K Q_K(x_p) r_K,
//
// so that particles that crowd (more of them per hat than the seeding put there, while the
// carried J stays near 1) count the water they span, not their number: the quadrature of
// eq. I2 weighs them by V0_p J_p and the volume error e_K = sum_p V0_p (J_p - 1) Q_K of eq. I3
// spreads them. r_K is capped at 1 where the hat is cut by the free surface (a neighbouring
// vertex, of the eight, holds less than kInside of its hat: a partly filled hat is not
// expanded water) and kept within [kLowest, kHighest] inside the water. A lattice of the
// seeding's spacing fills every hat exactly (the hat summed over a lattice of spacing h/2 is
// 2 per axis, at any offset, walls included), so water seeded at rest keeps J = 1.
#pragma once

#include <algorithm>
#include <vector>

#include "step/incompressible/pressure_grid.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class FillVolume {
 public:
  // r_K inside the water: at most 1.2, so that a void in the water (a hat holding a sixth
  // less water than it spans, or fewer particles still) is closed gently; at least 0.6, above
  // the density guard's default 0.5 (solver.density_range).
  static constexpr double kLowest = 0.6, kHighest = 1.2;
  static constexpr double kInside = 0.5;  // a neighbour whose hat holds this share is water

  void resize(const PressureGrid& grid) {
    grid_ = grid;
    fill_.assign(grid.count(), 0.0);
    ratio_.assign(grid.count(), 1.0);
  }
  std::size_t bytes() const { return heap_bytes(fill_) + heap_bytes(ratio_); }

  // Sets J_p of the particles of `bodies` (at x^k, with the step's weights) from the fill of
  // the hats of `vertices`, the box their cells' corners lie in.
  void apply(StepState<P>& st, const std::vector<int>& bodies, const NodeBox& vertices) {
    auto& ps = st.particles;
    const int ny = grid_.ny();
    // The strip order, as eq. I2's scatter: the same sums for any thread count.
    for (int b : bodies)
      st.schedules[b].for_each([&](std::uint32_t p) {
        const auto& w = st.weights[p];
        const PressureGrid::Hats q = grid_.at(ps.x[p], w.i0, w.j0);
        for (int ha = 0; ha < 2; ++ha)
          for (int hb = 0; hb < 2; ++hb) fill_[(w.i0 + ha) * ny + w.j0 + hb] += q.qx[ha] * q.qy[hb] * ps.volume0[p];
      });
    auto water = [&](int a, int b) {
      if (a < 0 || a > grid_.cells_x || b < 0 || b > grid_.cells_y) return true;  // beyond a wall
      return fill_[a * ny + b] >= kInside * grid_.hat_integral(a, b);
    };
#pragma omp parallel for schedule(static) if ((vertices.i1 - vertices.i0) * (vertices.j1 - vertices.j0) > 4096)
    for (int a = vertices.i0; a < vertices.i1; ++a)
      for (int b = vertices.j0; b < vertices.j1; ++b) {
        const int K = a * ny + b;
        if (!(fill_[K] > 0.0)) {
          ratio_[K] = 1.0;
          continue;
        }
        bool inside = true;
        for (int da = -1; da <= 1 && inside; ++da)
          for (int db = -1; db <= 1 && inside; ++db) inside = water(a + da, b + db);
        ratio_[K] = std::clamp(grid_.hat_integral(a, b) / fill_[K], kLowest, inside ? kHighest : 1.0);
      }
    for (int b : bodies) {
      const Body& body = st.bodies[b];
#pragma omp parallel for schedule(static)
      for (long p = static_cast<long>(body.begin); p < static_cast<long>(body.end); ++p) {
        const auto& w = st.weights[p];
        ps.J[p] = grid_.interpolate(grid_.at(ps.x[p], w.i0, w.j0), ratio_, grid_.index(w.i0, w.j0));
      }
    }
    for (int a = vertices.i0; a < vertices.i1; ++a)
      std::fill_n(fill_.begin() + a * ny + vertices.j0, vertices.j1 - vertices.j0, 0.0);
  }

 private:
  PressureGrid grid_;
  std::vector<double> fill_, ratio_;
};

}  // namespace bsmpm

// The excess volume of eq. I3 filtered before the projection feeds it back (docs/method.md
// §12, eq. I3f; solver.pressure.volume_correction_filter = n passes, 0 by default):
//
//   e_K <- e_K + 1/4 sum_N (e_N - e_K),   N the two neighbours of K along one axis,
//
// one pass along x then one along y, only between vertices whose hats are both at least half
// full (kFull) of water (volume0 >= kFull int Q_K). Inside the water a pass is the [1 2 1] / 4
// filter per axis, which removes the vertex-to-vertex alternation of e; each exchange is a
// flux between a pair, so the total excess volume is kept (to rounding) and eq. I3 still
// removes what the particles' motion added. Why half full: the surface vertices' excess is
// the surface's shape, not packing noise, and exchanging it with spray or a thin sheet
// (a hat holding a few particles) made a 2-vertex drop's A singular (the tank diverged).
// Each pass reads the last one's values only (Jacobi): the same bits for any thread count.
#pragma once

#include <algorithm>
#include <vector>

#include "grid/grid.hpp"
#include "step/incompressible/pressure_grid.hpp"

namespace bsmpm {

class ExcessVolumeFilter {
 public:
  static constexpr double kFull = 0.5;  // a hat this full exchanges excess volume with its neighbours

  void resize(const PressureGrid& grid) {
    grid_ = grid;
    excess_.assign(grid.count(), 0.0);
    scratch_.assign(grid.count(), 0.0);
    full_.assign(grid.count(), 0);
  }
  std::size_t bytes() const { return heap_bytes(excess_) + heap_bytes(scratch_) + heap_bytes(full_); }

  // Filters the excess volume of the vertices of `box` (vertex indices): `volume0(K)` is the
  // water the hat holds, sum_p V0_p Q_K, `excess(K)` e_K. The result is excess() on the box.
  template <class Volume0, class Excess>
  void apply(const NodeBox& box, int passes, Volume0&& volume0, Excess&& excess) {
    const int ny = grid_.ny();
    for (int a = box.i0; a < box.i1; ++a)
      for (int b = box.j0; b < box.j1; ++b) {
        const int K = a * ny + b;
        excess_[K] = excess(K);
        full_[K] = volume0(K) >= kFull * grid_.hat_integral(a, b);
      }
    for (int pass = 0; pass < passes; ++pass) {
      sweep(box, true);
      sweep(box, false);
    }
  }
  double excess(int K) const { return excess_[K]; }

 private:
  // One pass along x (neighbours K -+ ny) or y (K -+ 1), within the box.
  void sweep(const NodeBox& box, bool along_x) {
    const int ny = grid_.ny(), stride = along_x ? ny : 1;
    const int first = along_x ? box.i0 : box.j0, last = (along_x ? box.i1 : box.j1) - 1;
#pragma omp parallel for schedule(static) if ((box.i1 - box.i0) * (box.j1 - box.j0) > 4096)
    for (int a = box.i0; a < box.i1; ++a)
      for (int b = box.j0; b < box.j1; ++b) {
        const int K = a * ny + b, s = along_x ? a : b;
        double e = excess_[K];
        if (full_[K]) {
          if (s > first && full_[K - stride]) e += 0.25 * (excess_[K - stride] - excess_[K]);
          if (s < last && full_[K + stride]) e += 0.25 * (excess_[K + stride] - excess_[K]);
        }
        scratch_[K] = e;
      }
    for (int a = box.i0; a < box.i1; ++a)
      std::copy_n(scratch_.begin() + a * ny + box.j0, box.j1 - box.j0, excess_.begin() + a * ny + box.j0);
  }

  PressureGrid grid_;
  std::vector<double> excess_, scratch_;
  std::vector<char> full_;
};

}  // namespace bsmpm

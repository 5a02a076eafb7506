// Projection of the fluid's volumetric strain increment onto the B-splines one degree lower
// than the velocity's (docs/method.md §4): the B-bar / F-bar idea carried to B-spline MPM
// (Telikicherla & Moutsanidis 2024, CMAME, "Treatment of near-incompressibility and
// volumetric locking in higher order material point methods"), with the lower space of the
// isogeometric Taylor-Hood pair (velocity of degree p, pressure of degree p - 1 on the same
// knots; for p = 1 the cell-wise constants of the mean-dilatation method).
//
// With as many particles as there are per cell, the particles' volume ratios have far more
// freedom than the velocity field can control: particle-to-particle pressure modes that
// produce no nodal force are never corrected and grow into noise. Projecting the increment
// r_p = det(I + dt L_p) - 1 onto the lower space,
//   r_K = sum_p psi_K(x_p) V_p r_p / sum_p psi_K(x_p) V_p,   r_bar_p = sum_K psi_K(x_p) r_K
// (a locally lumped L2 projection), leaves J_p <- J_p (1 + r_bar_p) with only as many
// volumetric modes as the velocity can hold. Only the increment is projected: J itself is
// never averaged, so a pressure field with curvature (a stagnation point) is not diffused
// step after step.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "bspline/clamped_bspline.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class DilatationProjection {
  static constexpr int kLower = P - 1;          // degree of the pressure space
  static constexpr int kSupport = kLower + 1;   // its non-zero functions per axis at a point

 public:
  DilatationProjection() = default;
  explicit DilatationProjection(const Grid<P>& grid)
      : cells_x_(grid.bx.cells()), cells_y_(grid.by.cells()), ny_(cells_y_ + kLower),
        weighted_((cells_x_ + kLower) * ny_, 0.0), volume_((cells_x_ + kLower) * ny_, 0.0),
        origin_{grid.bx.origin(), grid.by.origin()}, inverse_cell_{1.0 / grid.bx.cell_size(), 1.0 / grid.by.cell_size()} {
    if constexpr (kLower > 0) {
      bx_ = ClampedBSpline<kLower>(grid.bx.origin(), grid.bx.cell_size(), grid.bx.cells());
      by_ = ClampedBSpline<kLower>(grid.by.origin(), grid.by.cell_size(), grid.by.cells());
    }
  }

  // Replaces increment[p] for the particles [begin, end) of one body by its projection.
  // The scatter runs in the body's strip order, so the sums do not depend on the threads.
  void project(const StepState<P>& st, const StripSchedule& schedule, long begin, long end,
               std::vector<double>& increment) {
    const Particles& ps = st.particles;
    int i_lo = cells_x_ + kLower, i_hi = 0;
    schedule.for_each([&](std::uint32_t p) {
      const Lower w = weights(ps.x[p]);
      const double V = ps.volume(p);
      for (int a = 0; a < kSupport; ++a)
        for (int c = 0; c < kSupport; ++c) {
          const int k = (w.i0 + a) * ny_ + w.j0 + c;
          const double s = w.wx[a] * w.wy[c] * V;
          weighted_[k] += s * increment[p];
          volume_[k] += s;
        }
    });
    // The columns the scatter wrote, from the positions it used (the particles' current ones,
    // which may have left the columns of the step's weights): all of them are cleared below.
#pragma omp parallel for schedule(static) reduction(min : i_lo) reduction(max : i_hi)
    for (long p = begin; p < end; ++p) {
      const int i0 = weights(ps.x[p]).i0;
      i_lo = std::min(i_lo, i0);
      i_hi = std::max(i_hi, i0 + kSupport);
    }
#pragma omp parallel for schedule(static)
    for (long p = begin; p < end; ++p) {
      const Lower w = weights(ps.x[p]);
      double r = 0.0;
      for (int a = 0; a < kSupport; ++a)
        for (int c = 0; c < kSupport; ++c) {
          const int k = (w.i0 + a) * ny_ + w.j0 + c;
          r += w.wx[a] * w.wy[c] * weighted_[k] / volume_[k];
        }
      increment[p] = r;
    }
    if (i_hi > i_lo) {
      std::fill(weighted_.begin() + i_lo * ny_, weighted_.begin() + i_hi * ny_, 0.0);
      std::fill(volume_.begin() + i_lo * ny_, volume_.begin() + i_hi * ny_, 0.0);
    }
  }

 private:
  struct Lower {
    int i0 = 0, j0 = 0;
    std::array<double, kSupport> wx{}, wy{};
  };
  // The lower-degree functions at x. Degree 0: the indicator of the particle's cell.
  Lower weights(const Vec2& x) const {
    Lower w;
    if constexpr (kLower == 0) {
      w.i0 = std::clamp(static_cast<int>(std::floor((x.x() - origin_[0]) * inverse_cell_[0])), 0, cells_x_ - 1);
      w.j0 = std::clamp(static_cast<int>(std::floor((x.y() - origin_[1]) * inverse_cell_[1])), 0, cells_y_ - 1);
      w.wx[0] = w.wy[0] = 1.0;
    } else {
      typename ClampedBSpline<kLower>::Weights dx, dy;
      w.i0 = bx_.evaluate(x.x(), w.wx, dx);
      w.j0 = by_.evaluate(x.y(), w.wy, dy);
    }
    return w;
  }

  int cells_x_ = 0, cells_y_ = 0, ny_ = 0;

 public:
  std::size_t bytes() const { return heap_bytes(weighted_) + heap_bytes(volume_); }

 private:
  std::vector<double> weighted_, volume_;  // sum psi V r and sum psi V per lower function
  std::array<double, 2> origin_{}, inverse_cell_{};
  ClampedBSpline<(kLower > 0 ? kLower : 1)> bx_, by_;
};

}  // namespace bsmpm

// Smoothing of the fluid's volume ratio through the grid (solver.fluid_volume = "smoothed";
// docs/method.md §4): at each control point a mass-weighted least-squares linear fit of the
// particles' J around its Greville point, J ~ J_I + g_I . (x - xi_I), then
// J_p = sum_I S_Ip (J_I + g_I . (x_p - xi_I)). It removes the particle-to-particle pressure
// noise of weakly compressible MPM. A plain mass average (Shepard) would take the value of the
// particles' centroid for the control point's, which next to a wall or a free surface lies a
// fraction of a cell inside: the fit reproduces linear J fields exactly, walls included. Where
// the particles around a control point do not span a plane (a thin film), the fit falls back
// to the mass average. The offsets x_p - xi_I use the particles' new positions x^{k+1}, where
// their J now sits; the step's weights S_Ip(x^k) only localise the fit, which stays exact for
// linear fields.
//
// Moments per control point, with d = (x_p - xi_I) / h:
// sum m S, sum m S d (2), sum m S d d^T (3), sum m S J, sum m S J d (2).
// S_Ip = N_a(x) N_c(y) and d = (dx_a, dy_c): every moment is a product of one factor per
// axis, N_a {1, dx_a, dx_a^2} times N_c {1, dy_c, dy_c^2}, formed once per particle.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <vector>

#include "step/passes/volume_fit.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class VolumeSmoothing {
 public:
  VolumeSmoothing() = default;
  VolumeSmoothing(const Grid<P>& grid, bool values_only)
      : moments_(kMoments * grid.node_count(), 0.0), rows_(grid.nx()),
        inverse_cell_(grid.cell_size().cwiseInverse()), values_only_(values_only) {}

  // Adds particle p's share of the moments (its J already updated); called in the scatter's
  // strip order, so the sums do not depend on the threads.
  void add_moments(const StepState<P>& st, std::uint32_t p) {
    double* const moments = moments_.data();
    const int ny = st.grid.ny();
    const double* const gx = st.grid.greville_x();
    const double* const gy = st.grid.greville_y();
    const Vec2& x = st.particles.x[p];
    const auto& w = st.weights[p];
    const double m = st.particles.mass[p], mJ = m * st.particles.J[p];
    // The rows written, per first column: a strip's particles alone have their first column
    // in it, so the strips running together never share an entry.
    RowRange& rows = rows_[w.i0];
    rows.first = std::min(rows.first, w.j0);
    rows.last = std::max(rows.last, w.j0);
    // The nine products in lane pairs (the same products and sums as one by one, so the
    // same bits): mom[0..1] = (x0, x1) y0, mom[2..3] = (x0 y1, x2 y0), mom[4..5] =
    // (x1 y1, x0 y2), mom[6..7] = (j0, j1) y0, mom[8] = j0 y1.
    std::array<Eigen::Array2d, P + 1> y00, y10, y12;  // N_c {1, dy, dy^2} paired
    std::array<double, P + 1> y1;
    for (int c = 0; c <= P; ++c) {
      const double dy = (x.y() - gy[w.j0 + c]) * inverse_cell_.y();
      const double y0 = w.wy[c];
      y1[c] = y0 * dy;
      const double y2 = y1[c] * dy;
      y00[c] = Eigen::Array2d(y0, y0);
      y10[c] = Eigen::Array2d(y1[c], y0);
      y12[c] = Eigen::Array2d(y1[c], y2);
    }
    for (int a = 0; a <= P; ++a) {
      const double dx = (x.x() - gx[w.i0 + a]) * inverse_cell_.x();
      const double x0 = m * w.wx[a], x1 = x0 * dx, x2 = x1 * dx;
      const double j0 = mJ * w.wx[a], j1 = j0 * dx;
      const Eigen::Array2d x01(x0, x1), x02(x0, x2), x10(x1, x0), j01(j0, j1);
      double* mom = moments + kMoments * ((w.i0 + a) * ny + w.j0);
      for (int c = 0; c <= P; ++c, mom += kMoments) {
        Eigen::Map<Eigen::Array2d>(mom + 0) += x01 * y00[c];
        Eigen::Map<Eigen::Array2d>(mom + 2) += x02 * y10[c];
        Eigen::Map<Eigen::Array2d>(mom + 4) += x10 * y12[c];
        Eigen::Map<Eigen::Array2d>(mom + 6) += j01 * y00[c];
        mom[8] += j0 * y1[c];
      }
    }
  }

  // Each written control point's fit (volume_fit.hpp), in the columns of the box b: those of
  // the particles' stencils (the untouched ones have no mass and stay zero).
  void fit(const NodeBox& b, int ny) {
#pragma omp parallel for schedule(static)
    for (int i = b.i0; i < b.i1; ++i) {
      const auto [j0, j1] = rows_written(i);
      for (int j = j0; j < j1; ++j) fit_volume_moments(&moments_[kMoments * (i * ny + j)]);
    }
  }

  // J_p = sum_I S_Ip (J_I + g_I . (x_p - xi_I)) from the fitted control points, or with
  // values only, J_p = sum_I S_Ip J_I. Both reproduce a linear J (sum_I S_Ip xi_I = x_p, walls
  // included). With the gradients, particles bunched in columns at the knots, two columns in
  // each control point's support, get back exactly the J they gave: the fit passes any
  // column-to-column pattern through (the pressure stripes of docs/validation.md). The values
  // alone average each column with its neighbours (weights 1/4, 1/2, 1/4).
  double fitted_volume_ratio(const StepState<P>& st, std::size_t p) const {
    if (values_only_) return fitted_value(st, p);
    const int ny = st.grid.ny();
    const double* const gx = st.grid.greville_x();
    const double* const gy = st.grid.greville_y();
    const Vec2& x = st.particles.x[p];
    const auto& w = st.weights[p];
    std::array<double, P + 1> dy;
    for (int c = 0; c <= P; ++c) dy[c] = (x.y() - gy[w.j0 + c]) * inverse_cell_.y();
    double J = 0.0;
    for (int a = 0; a <= P; ++a) {
      const double dx = (x.x() - gx[w.i0 + a]) * inverse_cell_.x();
      const double* fit = &moments_[kMoments * ((w.i0 + a) * ny + w.j0)];
      double row = 0.0;
      for (int c = 0; c <= P; ++c, fit += kMoments) row += w.wy[c] * (fit[0] + fit[1] * dx + fit[2] * dy[c]);
      J += w.wx[a] * row;
    }
    return J;
  }

  // J_p = sum_I S_Ip J_I.
  double fitted_value(const StepState<P>& st, std::size_t p) const {
    const int ny = st.grid.ny();
    const auto& w = st.weights[p];
    double J = 0.0;
    for (int a = 0; a <= P; ++a) {
      const double* fit = &moments_[kMoments * ((w.i0 + a) * ny + w.j0)];
      double row = 0.0;
      for (int c = 0; c <= P; ++c, fit += kMoments) row += w.wy[c] * fit[0];
      J += w.wx[a] * row;
    }
    return J;
  }

  // Zeroes the control points written, in the columns of the box b, for the next step: with
  // the water spread over the tank the box is mostly empty (validation.md, Speed).
  void clear(const NodeBox& b, int ny) {
#pragma omp parallel for schedule(static) if ((b.i1 - b.i0) * (b.j1 - b.j0) > 4096)
    for (int i = b.i0; i < b.i1; ++i) {
      const auto [j0, j1] = rows_written(i);
      if (j0 < j1) std::fill_n(moments_.begin() + kMoments * (i * ny + j0), kMoments * (j1 - j0), 0.0);
    }
    std::fill(rows_.begin() + b.i0, rows_.begin() + b.i1, RowRange{});
  }

  std::size_t bytes() const { return heap_bytes(moments_) + heap_bytes(rows_); }

 private:
  static constexpr int kMoments = 9;
  static constexpr int kNoRow = std::numeric_limits<int>::max();

  // The rows [j0, j1) of column i that particles wrote to: those of the particles whose
  // first column is i - P ... i (empty when none; the range may span rows between two groups).
  std::pair<int, int> rows_written(int i) const {
    int j0 = kNoRow, j1 = -1;
    for (int a = std::max(i - P, 0); a <= i; ++a) {
      j0 = std::min(j0, rows_[a].first);
      j1 = std::max(j1, rows_[a].last);
    }
    return {j0, j1 + P + 1};
  }

  // The least and greatest first row of the particles whose stencil's first column is this
  // one (kNoRow / -1: none); read by fit() and clear(), reset by clear().
  struct RowRange {
    int first = kNoRow, last = -1;
  };

  std::vector<double> moments_;  // per control point
  std::vector<RowRange> rows_;   // per column
  Vec2 inverse_cell_ = Vec2::Zero();
  bool values_only_ = false;
};

}  // namespace bsmpm

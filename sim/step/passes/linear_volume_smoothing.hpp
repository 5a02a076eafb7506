// The fluid's volume ratio fitted through the linear B-splines (the hats) on the velocity's
// knots (solver.smoothed_volume_basis = "linear"; docs/method.md §4): the least-squares
// linear fit of VolumeSmoothing, J ~ J_K + g_K . (x - x_K) about each knot x_K with the hat
// psi_K as the weight, then J_p = sum_K psi_K(x_p) (J_K + g_K . (x_p - x_K)). A particle
// touches 2 x 2 knots instead of (P + 1)^2 control points (36 scattered moments instead of
// 81 for P = 2); the fit stays exact for linear J, walls included (sum_K psi_K x_K = x_p).
// The hats are taken at the particles' new positions x^{k+1}, where their J now sits.
// With patches (solver.smoothed_volume_basis = "linear_patches") the fit's weight is 1 over
// the four cells around each knot instead of psi_K (method.md §4, eq. S2): a particle adds
// its nine moments to its own cell only, and a grid pass carries the cells' moments to the
// knots; the readback is the same.
//
// Moments per knot, with d = (x_p - x_K) / h: sum m psi, sum m psi d (2), sum m psi d d^T
// (3), sum m psi J, sum m psi J d (2); the fit (volume_fit.hpp) replaces the first three.
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
class LinearVolumeSmoothing {
 public:
  LinearVolumeSmoothing() = default;
  LinearVolumeSmoothing(const Grid<P>& grid, bool values_only, bool patches)
      : cells_x_(grid.bx.cells()), cells_y_(grid.by.cells()), ny_(cells_y_ + 1),
        moments_(kMoments * std::size_t(cells_x_ + 1) * (cells_y_ + 1), 0.0), rows_(cells_x_ + 1),
        origin_(grid.origin()), inverse_cell_(grid.cell_size().cwiseInverse()), values_only_(values_only),
        patches_(patches) {}

  // Adds particle p's share of the moments (its J already updated); called in the scatter's
  // strip order, so the sums do not depend on the threads.
  void add_moments(const StepState<P>& st, std::uint32_t p) {
    const Hats h = hats(st, p);
    const double m = st.particles.mass[p], mJ = m * st.particles.J[p];
    // The rows written, per cell column: a strip's particles move less than a cell, so the
    // strips running together never share an entry (the moments' own margin).
    RowRange& rows = rows_[h.i];
    rows.first = std::min(rows.first, h.j);
    rows.last = std::max(rows.last, h.j);
    double* mom = moments_.data() + kMoments * (std::size_t(h.i) * ny_ + h.j);
    if (patches_) {
      // The cell's moments about its first knot, d = (tx, ty); fit() carries them to the knots.
      const double tx = h.dx[0], ty = h.dy[0], mx = m * tx, my = m * ty, jx = mJ * tx;
      Eigen::Map<Eigen::Array2d>(mom + 0) += Eigen::Array2d(m, mx);
      Eigen::Map<Eigen::Array2d>(mom + 2) += Eigen::Array2d(my, mx) * Eigen::Array2d(1.0, tx);
      Eigen::Map<Eigen::Array2d>(mom + 4) += Eigen::Array2d(mx, my) * Eigen::Array2d(ty, ty);
      Eigen::Map<Eigen::Array2d>(mom + 6) += Eigen::Array2d(mJ, jx);
      mom[8] += mJ * ty;
      return;
    }
    // The nine products in lane pairs, as VolumeSmoothing forms them.
    std::array<Eigen::Array2d, 2> y00, y10, y12;
    std::array<double, 2> y1;
    for (int c = 0; c < 2; ++c) {
      const double y0 = h.wy[c];
      y1[c] = y0 * h.dy[c];
      const double y2 = y1[c] * h.dy[c];
      y00[c] = Eigen::Array2d(y0, y0);
      y10[c] = Eigen::Array2d(y1[c], y0);
      y12[c] = Eigen::Array2d(y1[c], y2);
    }
    for (int a = 0; a < 2; ++a, mom += kMoments * (ny_ - 2)) {
      const double x0 = m * h.wx[a], x1 = x0 * h.dx[a], x2 = x1 * h.dx[a];
      const double j0 = mJ * h.wx[a], j1 = j0 * h.dx[a];
      const Eigen::Array2d x01(x0, x1), x02(x0, x2), x10(x1, x0), j01(j0, j1);
      for (int c = 0; c < 2; ++c, mom += kMoments) {
        Eigen::Map<Eigen::Array2d>(mom + 0) += x01 * y00[c];
        Eigen::Map<Eigen::Array2d>(mom + 2) += x02 * y10[c];
        Eigen::Map<Eigen::Array2d>(mom + 4) += x10 * y12[c];
        Eigen::Map<Eigen::Array2d>(mom + 6) += j01 * y00[c];
        mom[8] += j0 * y1[c];
      }
    }
  }

  // Before the scatter: the knots of this step, those of the control points' box `b` (the
  // body's at x^k, method.md §2 step 1) and a cell beyond, where the particles now are.
  void begin(const NodeBox& b) {
    box_ = {std::max(b.i0 - 1, 0), std::min(b.i1 + 1, cells_x_ + 1), std::max(b.j0 - 1, 0),
            std::min(b.j1 + 1, cells_y_ + 1)};
    first_cell_ = {double(box_.i0), double(box_.j0)};
    last_cell_x_ = std::max(box_.i1 - 2, box_.i0);
    last_cell_y_ = std::max(box_.j1 - 2, box_.j0);
  }

  // The fit at the knots written (the others have no mass and stay zero).
  void fit() {
    if (patches_) cells_to_knots();
#pragma omp parallel for schedule(static)
    for (int i = box_.i0; i < box_.i1; ++i) {
      const auto [j0, j1] = rows_written(i);
      for (int j = j0; j < j1; ++j) fit_volume_moments(&moments_[kMoments * (std::size_t(i) * ny_ + j)]);
    }
  }

  // With patches, each knot's moments from the cells around it (in place: knot K replaces
  // cell K, the cells K - 1 read before they are replaced), along x then along y. A cell's
  // moments about the knot one cell below it in an axis are those about its own first knot
  // with d shifted by -1 in that axis.
  void cells_to_knots() {
    const int ny = ny_;
#pragma omp parallel for schedule(static)
    for (int j = box_.j0; j < box_.j1; ++j)
      for (int i = box_.i1 - 1; i > box_.i0; --i) {
        double* k = &moments_[kMoments * (std::size_t(i) * ny + j)];
        const double* c = k - kMoments * ny;  // cell i - 1, seen from knot i: dx - 1
        if (c[0] == 0.0) continue;            // no water there (most of the box, later in a run)
        k[0] += c[0];
        k[1] += c[1] - c[0];
        k[2] += c[2];
        k[3] += c[3] - 2.0 * c[1] + c[0];
        k[4] += c[4] - c[2];
        k[5] += c[5];
        k[6] += c[6];
        k[7] += c[7] - c[6];
        k[8] += c[8];
      }
#pragma omp parallel for schedule(static)
    for (int i = box_.i0; i < box_.i1; ++i)
      for (int j = box_.j1 - 1; j > box_.j0; --j) {
        double* k = &moments_[kMoments * (std::size_t(i) * ny + j)];
        const double* c = k - kMoments;  // cell j - 1, seen from knot j: dy - 1
        if (c[0] == 0.0) continue;
        k[0] += c[0];
        k[1] += c[1];
        k[2] += c[2] - c[0];
        k[3] += c[3];
        k[4] += c[4] - c[1];
        k[5] += c[5] - 2.0 * c[2] + c[0];
        k[6] += c[6];
        k[7] += c[7];
        k[8] += c[8] - c[6];
      }
  }

  // J_p = sum_K psi_K (J_K + g_K . (x_p - x_K)), or with values only sum_K psi_K J_K.
  [[gnu::always_inline]] double fitted_volume_ratio(const StepState<P>& st, std::size_t p) const {
    const Hats h = hats(st, p);
    const double* f0 = moments_.data() + kMoments * (std::size_t(h.i) * ny_ + h.j);  // knots (i, j), (i, j + 1)
    const double* f1 = f0 + kMoments * ny_;                                          // (i + 1, j), (i + 1, j + 1)
    if (values_only_)
      return h.wx[0] * (h.wy[0] * f0[0] + h.wy[1] * f0[kMoments]) + h.wx[1] * (h.wy[0] * f1[0] + h.wy[1] * f1[kMoments]);
    const double* f01 = f0 + kMoments;
    const double* f11 = f1 + kMoments;
    const double row0 = h.wy[0] * (f0[0] + f0[1] * h.dx[0] + f0[2] * h.dy[0]) +
                        h.wy[1] * (f01[0] + f01[1] * h.dx[0] + f01[2] * h.dy[1]);
    const double row1 = h.wy[0] * (f1[0] + f1[1] * h.dx[1] + f1[2] * h.dy[0]) +
                        h.wy[1] * (f11[0] + f11[1] * h.dx[1] + f11[2] * h.dy[1]);
    return h.wx[0] * row0 + h.wx[1] * row1;
  }

  // Zeroes the knots written for the next step: with the water spread over the tank the box
  // is mostly empty (validation.md, Speed).
  void clear() {
#pragma omp parallel for schedule(static) if ((box_.i1 - box_.i0) * (box_.j1 - box_.j0) > 4096)
    for (int i = box_.i0; i < box_.i1; ++i) {
      const auto [j0, j1] = rows_written(i);
      if (j0 < j1) std::fill_n(moments_.begin() + kMoments * (std::size_t(i) * ny_ + j0), kMoments * (j1 - j0), 0.0);
    }
    std::fill(rows_.begin() + box_.i0, rows_.begin() + box_.i1, RowRange{});
  }

  std::size_t bytes() const { return heap_bytes(moments_) + heap_bytes(rows_); }

 private:
  static constexpr int kMoments = 9;
  static constexpr int kNoRow = std::numeric_limits<int>::max();
  // The least and greatest row of the cells the particles wrote to, per cell column (kNoRow /
  // -1: none); read by fit() and clear(), reset by clear().
  struct RowRange {
    int first = kNoRow, last = -1;
  };

  // The rows [j0, j1) of knot column i written: those of cells i - 1 and i and a knot above
  // (the patches' carry to the knots reaches no further); the range may span empty rows.
  std::pair<int, int> rows_written(int i) const {
    int j0 = kNoRow, j1 = -1;
    for (int a = std::max(i - 1, 0); a <= i && a <= cells_x_; ++a) {
      j0 = std::min(j0, rows_[a].first);
      j1 = std::max(j1, rows_[a].last);
    }
    return {j0, j1 + 2};
  }

  // The particle's cell (i, j) = its first knot, the hats' values and the offsets
  // d = (x - x_K) / h of its four knots.
  struct Hats {
    int i = 0, j = 0;
    double wx[2], wy[2], dx[2], dy[2];
  };
  // The particle's cell at x^{k+1}, held inside the step's box (begin()): a particle moves
  // less than a cell in a step (the time step's CFL bound), and the hold keeps every write
  // inside the box that is fitted and cleared whatever the step did (a particle held there
  // reads the hats extrapolated, still a partition of unity exact for linear J). As for the
  // F-bar projection, the strips' margin (method.md §9) assumes moves of less than 5 cells.
  // Truncation is the floor here (u >= the first cell), and SSE2 has no rounding
  // instruction: std::floor would be a call.
  [[gnu::always_inline]] Hats hats(const StepState<P>& st, std::size_t p) const {
    const Vec2& x = st.particles.x[p];
    const double ux = (x.x() - origin_.x()) * inverse_cell_.x(), uy = (x.y() - origin_.y()) * inverse_cell_.y();
    Hats h;
    h.i = std::min(static_cast<int>(std::max(ux, first_cell_[0])), last_cell_x_);
    h.j = std::min(static_cast<int>(std::max(uy, first_cell_[1])), last_cell_y_);
    const double tx = ux - h.i, ty = uy - h.j;
    h.wx[0] = 1.0 - tx, h.wx[1] = tx, h.dx[0] = tx, h.dx[1] = tx - 1.0;
    h.wy[0] = 1.0 - ty, h.wy[1] = ty, h.dy[0] = ty, h.dy[1] = ty - 1.0;
    return h;
  }

  int cells_x_ = 0, cells_y_ = 0, ny_ = 0;
  std::vector<double> moments_;  // per knot
  std::vector<RowRange> rows_;   // per cell column
  Vec2 origin_ = Vec2::Zero(), inverse_cell_ = Vec2::Zero();
  bool values_only_ = false;
  bool patches_ = false;  // fit weights 1 over each knot's four cells instead of its hat
  NodeBox box_;  // knots fitted this step, cleared after the readback
  std::array<double, 2> first_cell_{};   // the box's first cell per axis
  int last_cell_x_ = 0, last_cell_y_ = 0;  // its last cell per axis
};

}  // namespace bsmpm

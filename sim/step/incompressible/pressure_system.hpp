// The pressure equation of the incompressible fluid (docs/method.md §12, eq. I4):
//
//   (D W D^T + alpha/rho0 S) p = b,
//
// on the vertices that hold water (the unknowns), with W the inverse lumped nodal masses
// per free velocity component (a component a wall or a light node fixes drops out: the
// projection leaves it alone, which is how the walls' v.n = 0 enters), and S the sum over
// every three consecutive unknown vertices along a grid line of (p_{k-1} - 2 p_k + p_{k+1})^2:
// zero on linear pressure fields, it lifts the one pressure mode D^T does not see (the
// vertex checkerboard, method.md §12) without touching hydrostatic or linear fields.
// Matrix-free: A x = D (W (D^T x)) + alpha/rho0 S x, gathered per control point and per
// vertex in a fixed order, so that any thread count gives the same bits.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include "step/incompressible/divergence_operator.hpp"

namespace bsmpm {

// Which velocity components of a control point the projection may not change.
enum FixedComponent : std::uint8_t { kFixedX = 1, kFixedY = 2 };

template <int P>
class PressureSystem {
 public:
  void resize(const PressureGrid& grid, int node_nx, int node_ny) {
    grid_ = grid;
    node_nx_ = node_nx;
    node_ny_ = node_ny;
    position_.assign(grid.count(), -1);
    scratch_.assign(grid.count(), 0.0);
    second_x_.assign(grid.count(), 0.0);
    second_y_.assign(grid.count(), 0.0);
    stencil_.assign(grid.count(), 0);
    inverse_mass_.assign(std::size_t(node_nx) * node_ny, Vec2::Zero());
    force_.assign(std::size_t(node_nx) * node_ny, Vec2::Zero());
  }
  std::size_t bytes() const {
    return heap_bytes(position_) + heap_bytes(scratch_) + heap_bytes(second_x_) + heap_bytes(second_y_) +
           heap_bytes(stencil_) + heap_bytes(inverse_mass_) + heap_bytes(force_) + heap_bytes(unknowns_) +
           heap_bytes(diagonal_) + heap_bytes(assembly_);
  }

  // The unknowns: vertices of `vertices` whose hat is filled to at least `fraction` (volume
  // fraction sum_p V_p Q_K / integral of Q_K); W from the nodal masses of `nodes`.
  void find_unknowns(const DivergenceOperator<P>& D, const NodeBox& vertices, const NodeBox& nodes, double fraction,
                     double stabilization) {
    D_ = &D;
    nodes_ = nodes;
    vertices_ = vertices;
    stabilization_ = stabilization;
    const int ny = grid_.ny();
    for (int K : unknowns_) {  // the last step's marks, so that no vertex keeps one it no longer has
      position_[K] = -1;
      stencil_[K] = 0;
    }
    unknowns_.clear();
    for (int a = vertices.i0; a < vertices.i1; ++a)
      for (int b = vertices.j0; b < vertices.j1; ++b) {
        const int K = a * ny + b;
        // The water's reference volume: compressed water fills its hat as uncompressed water
        // would, so a compressing cluster is held, not let go as spray.
        if (D.moments(K).volume0 >= fraction * grid_.hat_integral(a, b)) {
          position_[K] = static_cast<int>(unknowns_.size());
          unknowns_.push_back(K);
        }
      }
    // Three consecutive unknowns along x (bit 0) or y (bit 1) centred on K: a term of S.
    for (int K : unknowns_) {
      const int a = K / ny, b = K % ny;
      std::uint8_t s = 0;
      if (a > 0 && a < grid_.cells_x && position_[K - ny] >= 0 && position_[K + ny] >= 0) s |= 1;
      if (b > 0 && b < grid_.cells_y && position_[K - 1] >= 0 && position_[K + 1] >= 0) s |= 2;
      stencil_[K] = s;
    }
  }

  // W: the inverse nodal masses of `layer`, zero for a component in `fixed` (FixedComponent
  // bits per control point) and on nodes at or below the mass cut-off; then A's diagonal.
  void set_weights(const GridLayer& layer, const std::vector<std::uint8_t>& fixed, double mass_cutoff) {
    for_each_node([&](int n, int, int) {
      const double m = layer.mass[n];
      const double inv = m > mass_cutoff ? 1.0 / m : 0.0;
      inverse_mass_[n] = Vec2(fixed[n] & kFixedX ? 0.0 : inv, fixed[n] & kFixedY ? 0.0 : inv);
    });
    compute_diagonal();
  }

  int size() const { return static_cast<int>(unknowns_.size()); }
  const PressureGrid& grid() const { return grid_; }
  const std::vector<int>& unknowns() const { return unknowns_; }
  const std::vector<double>& diagonal() const { return diagonal_; }
  const Vec2& inverse_mass(int node) const { return inverse_mass_[node]; }

  // y = A x on the unknowns.
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    const int n = size();
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) scratch_[unknowns_[k]] = x[k];
    pressure_force(scratch_, force_);
    for_each_node([&](int node, int, int) { force_[node] = force_[node].cwiseProduct(inverse_mass_[node]); });
    if (stabilization_ > 0.0) second_differences(scratch_);
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      const int K = unknowns_[k];
      y[k] = D_->row_times(K, force_) + (stabilization_ > 0.0 ? stabilization_ * stabilizer_at(K) : 0.0);
    }
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      const int K = unknowns_[k];
      scratch_[K] = second_x_[K] = second_y_[K] = 0.0;
    }
  }

  // f_I = (D^T p)_I on the nodes: the pressure's force on the control points (eq. 7 with
  // sigma = -p I); p on the whole vertex grid, zero off the unknowns.
  void pressure_force(const std::vector<double>& p, std::vector<Vec2>& f) const {
    for_each_node_parallel(nodes_, node_ny_, [&](int n, int i, int j) { f[n] = D_->transpose_at(p, i, j); });
  }

  template <class F>
  void for_each_node(F&& f) const {
    for_each_node_parallel(nodes_, node_ny_, f);
  }

  // A assembled (row-major, the unknowns' order): row k holds the (2P + 3)^2 vertices within
  // reach of vertex K through a shared control point, summed per row in a fixed order. A is
  // symmetric: each row sums only its entries from K on (vertex order), the others are read
  // from the rows that summed them, so A is symmetric to the bit and costs half the products.
  void assemble(Eigen::SparseMatrix<double, Eigen::RowMajor>& A) const {
    constexpr int kSpan = DivergenceOperator<P>::kSpan, kReach = 2 * kSpan - 1, kCentre = kSpan - 1;
    const int n = size(), ny = grid_.ny();
    std::vector<double>& local = assembly_;
    local.assign(std::size_t(n) * kReach * kReach, 0.0);
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      const int K = unknowns_[k], a = K / ny, b = K % ny;
      double* const row = local.data() + std::size_t(k) * kReach * kReach;
      // A_KL = sum_I D_KI W_I D_LI over the control points I = (a - 1 + e, b - 1 + f) of K's
      // row; L = (a + e - e2, b + f - f2) meets I at its own offset (e2, f2), and lies from K
      // on where e2 < e, or e2 = e and f2 <= f. Every such vertex L on the grid is summed (the
      // rows of vertices without water hold what their particles put there; compressing drops
      // them), in the order of I, then (e2, f2).
      const Vec2* const dk = D_->row(K);
      for (int e = 0; e < kSpan; ++e) {
        const int i = a - 1 + e;
        if (i < 0 || i >= node_nx_) continue;
        const int e2_lo = std::max(0, a + e - grid_.cells_x), e2_hi = std::min(e, a + e);
        for (int f = 0; f < kSpan; ++f) {
          const int j = b - 1 + f;
          if (j < 0 || j >= node_ny_) continue;
          const int I = i * node_ny_ + j;
          const Vec2 dw = dk[e * kSpan + f].cwiseProduct(inverse_mass_[I]);
          if (dw.isZero(0.0)) continue;
          const int f2_lo = std::max(0, b + f - grid_.cells_y), f2_all = std::min(kSpan - 1, b + f);
          for (int e2 = e2_lo; e2 <= e2_hi; ++e2) {
            const int f2_hi = e2 == e ? std::min(f, f2_all) : f2_all;
            const int L0 = K + (e - e2) * ny + f;                                  // L at f2 = 0
            double* const out = row + (e - e2 + kCentre) * kReach + f + kCentre;  // its entry
            for (int f2 = f2_lo; f2 <= f2_hi; ++f2) out[-f2] += dw.dot(D_->row(L0 - f2)[e2 * kSpan + f2]);
          }
        }
      }
      if (stabilization_ > 0.0)
        for (int axis = 0; axis < 2; ++axis) {
          const int step = axis == 0 ? ny : 1, bit = axis == 0 ? 1 : 2;
          for (int c = -1; c <= 1; ++c) {
            const int C = K + c * step;
            if (C < 0 || C >= grid_.count() || position_[C] < 0 || !(stencil_[C] & bit)) continue;
            const double cK = c == 0 ? -2.0 : 1.0;
            for (int l = std::max(-1, -c); l <= 1; ++l) {
              const int off = c + l;  // L = C + l step = K + (c + l) step, from K on
              const int da = axis == 0 ? off : 0, db = axis == 0 ? 0 : off;
              row[(da + kCentre) * kReach + db + kCentre] += stabilization_ * cK * (l == 0 ? -2.0 : 1.0);
            }
          }
        }
    }
    // Written in place, compressed (rows come out sorted since the unknowns are numbered in
    // vertex order), into storage reused from step to step: the rows' lengths, then the rows,
    // side by side. An entry before K is row L's entry at the mirrored offset.
    auto entry = [&](int k, int da, int db, int l) {
      const bool before = da < kCentre || (da == kCentre && db < kCentre);
      return before ? local[std::size_t(l) * kReach * kReach + (2 * kCentre - da) * kReach + 2 * kCentre - db]
                    : local[std::size_t(k) * kReach * kReach + da * kReach + db];
    };
    auto for_each_entry = [&](int k, auto&& visit) {
      const int K = unknowns_[k], a = K / ny, b = K % ny;
      for (int da = 0; da < kReach; ++da) {
        const int la = a + da - kCentre;
        if (la < 0 || la > grid_.cells_x) continue;
        for (int db = 0; db < kReach; ++db) {
          const int lb = b + db - kCentre;
          if (lb < 0 || lb > grid_.cells_y) continue;
          const int l = position_[la * ny + lb];
          if (l < 0) continue;
          const double v = entry(k, da, db, l);
          if (v != 0.0) visit(l, v);
        }
      }
    };
    A.resize(n, n);
    int* const outer = A.outerIndexPtr();
    outer[0] = 0;
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      int count = 0;
      for_each_entry(k, [&](int, double) { ++count; });
      outer[k + 1] = count;
    }
    for (int k = 0; k < n; ++k) outer[k + 1] += outer[k];
    A.data().resize(outer[n]);
    int* const inner = A.innerIndexPtr();
    double* const value = A.valuePtr();
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      int at = outer[k];
      for_each_entry(k, [&](int l, double v) {
        inner[at] = l;
        value[at++] = v;
      });
    }
  }

 private:
  // The second differences of x along x and y at every unknown that centres a term of S.
  void second_differences(const std::vector<double>& x) const {
    const int ny = grid_.ny(), n = size();
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      const int K = unknowns_[k];
      second_x_[K] = stencil_[K] & 1 ? x[K - ny] - 2.0 * x[K] + x[K + ny] : 0.0;
      second_y_[K] = stencil_[K] & 2 ? x[K - 1] - 2.0 * x[K] + x[K + 1] : 0.0;
    }
  }

  // (S x)_K: each term of S is d (d . x) with d = (1, -2, 1) along its line, so K collects
  // -2 times the term it centres and once each term it ends (second_x_, second_y_ are zero
  // off the centres).
  double stabilizer_at(int K) const {
    const int ny = grid_.ny(), a = K / ny, b = K % ny;
    double s = -2.0 * (second_x_[K] + second_y_[K]);
    if (a > 0) s += second_x_[K - ny];
    if (a < grid_.cells_x) s += second_x_[K + ny];
    if (b > 0) s += second_y_[K - 1];
    if (b < grid_.cells_y) s += second_y_[K + 1];
    return s;
  }

  void compute_diagonal() {
    const int n = size(), ny = grid_.ny();
    diagonal_.resize(n);
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      const int K = unknowns_[k], a = K / ny, b = K % ny;
      double sum = 0.0;
      D_->for_each_in_row(K, [&](const Vec2& d, int I) { sum += d.cwiseAbs2().dot(inverse_mass_[I]); });
      // S's diagonal: 4 for the term centred on K, 1 for each term it ends.
      double s = (stencil_[K] & 1 ? 4.0 : 0.0) + (stencil_[K] & 2 ? 4.0 : 0.0);
      if (a > 0 && stencil_[K - ny] & 1) s += 1.0;
      if (a < grid_.cells_x && stencil_[K + ny] & 1) s += 1.0;
      if (b > 0 && stencil_[K - 1] & 2) s += 1.0;
      if (b < grid_.cells_y && stencil_[K + 1] & 2) s += 1.0;
      diagonal_[k] = sum + stabilization_ * s;
    }
  }

  PressureGrid grid_;
  int node_nx_ = 0, node_ny_ = 0;
  const DivergenceOperator<P>* D_ = nullptr;
  NodeBox nodes_, vertices_;
  double stabilization_ = 0.0;  // alpha / rho0
  std::vector<int> position_;   // vertex -> unknown index, -1 if none
  std::vector<int> unknowns_;   // unknown index -> vertex
  std::vector<std::uint8_t> stencil_;
  std::vector<Vec2> inverse_mass_;
  std::vector<double> diagonal_;
  mutable std::vector<double> scratch_, second_x_, second_y_;
  mutable std::vector<double> assembly_;  // assemble's rows, (2P + 3)^2 per unknown
  mutable std::vector<Vec2> force_;
};

// The operator as Eigen's iterative solvers see it (Eigen's matrix-free example).
template <int P>
class PressureMatrix : public Eigen::EigenBase<PressureMatrix<P>> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = false };
  explicit PressureMatrix(const PressureSystem<P>* system = nullptr) : system_(system) {}
  Eigen::Index rows() const { return system_->size(); }
  Eigen::Index cols() const { return system_->size(); }
  template <class Rhs>
  Eigen::Product<PressureMatrix, Rhs, Eigen::AliasFreeProduct> operator*(const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<PressureMatrix, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }
  const PressureSystem<P>& system() const { return *system_; }

 private:
  const PressureSystem<P>* system_;
};

}  // namespace bsmpm

namespace Eigen::internal {

template <int P>
struct traits<bsmpm::PressureMatrix<P>> : public traits<Eigen::SparseMatrix<double>> {};

template <int P, class Rhs>
struct generic_product_impl<bsmpm::PressureMatrix<P>, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<bsmpm::PressureMatrix<P>, Rhs,
                                generic_product_impl<bsmpm::PressureMatrix<P>, Rhs>> {
  template <class Dest>
  static void scaleAndAddTo(Dest& dst, const bsmpm::PressureMatrix<P>& lhs, const Rhs& rhs, const double& alpha) {
    static thread_local Eigen::VectorXd x, y;
    x = rhs;
    y.resize(x.size());
    lhs.system().apply(x, y);
    dst += alpha * y;
  }
};

}  // namespace Eigen::internal

// A geometric multigrid V-cycle as the preconditioner of the pressure solve (docs/method.md
// §12, "The solve"): the iterations of incomplete Cholesky's CG grow as 1/h, a multigrid's
// do not. The unknowns are vertices of the cell-corner grid; each coarser level keeps every
// other vertex per axis, its unknowns the coarse vertices whose block {2c, 2c+1} x {2d, 2d+1}
// holds a finer unknown, and its prolongation P is the bilinear interpolation restricted to
// the unknowns (a coarse vertex that is not an unknown carries 0, as p does past the free
// surface). The coarse operators are Galerkin's, A_c = P^T A P, from the assembled A itself,
// so the coarse levels see the walls, the light nodes and the stabilization as the fine one
// does. Each of its columns has a row in its own block whose other entries lie up and to the
// right, so P has full rank and A_c is symmetric positive definite with A.
//
// One V-cycle with a forward Gauss-Seidel sweep before the coarse correction and a backward
// one after it (the adjoint), and the coarsest level solved exactly (sparse LDL^T), is a
// symmetric positive definite operator: a preconditioner conjugate gradients accept. Every
// loop is serial in a fixed order (the same bits for any thread count), and the levels keep
// their storage from step to step.
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace bsmpm {

class MultigridPreconditioner : public Eigen::SparseSolverBase<MultigridPreconditioner> {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  // A level of at most this many unknowns is solved exactly (default 400).
  void set_coarsest(int unknowns) { coarsest_size_ = unknowns; }

  // The unknowns' vertices K = a * ny + b on the nx x ny vertex grid, in A's order; set
  // before compute().
  void set_vertices(int nx, int ny, const std::vector<int>& unknowns) {
    nx_ = nx;
    ny_ = ny;
    vertices_ = &unknowns;
  }

  // A compressed row-major sparse matrix (or a Ref to one, as ConjugateGradient passes it);
  // it must outlive the solve, which reads it in place.
  template <class M>
  MultigridPreconditioner& analyzePattern(const M&) {
    return *this;
  }
  template <class M>
  MultigridPreconditioner& factorize(const M& A) {
    return compute(A);
  }
  template <class M>
  MultigridPreconditioner& compute(const M& matrix) {
    eigen_assert(matrix.isCompressed());
    fine_.emplace(matrix.rows(), matrix.cols(), matrix.nonZeros(), matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                  matrix.valuePtr());
    const FineMatrix& A = *fine_;
    depth_ = 0;
    int nx = nx_, ny = ny_;
    const std::vector<int>* vertices = vertices_;
    for (;;) {
      if (depth_ == static_cast<int>(levels_.size())) levels_.emplace_back();
      Level& level = levels_[depth_];
      const int rows = static_cast<int>(depth_ == 0 ? A.rows() : level.A.rows());
      level.n = rows;
      level.inverse_diagonal.resize(level.n);
      for (int i = 0; i < level.n; ++i) {
        const double d = depth_ == 0 ? A.coeff(i, i) : level.A.coeff(i, i);
        level.inverse_diagonal[i] = d > 0.0 ? 1.0 / d : 0.0;
      }
      level.x.resize(level.n);
      level.r.resize(level.n);
      if (level.n <= coarsest_size_ || nx <= 2 || ny <= 2 || !coarsen(level, nx, ny, *vertices)) break;
      Level& coarse = depth_ + 1 == static_cast<int>(levels_.size()) ? levels_.emplace_back() : levels_[depth_ + 1];
      Level& fine = levels_[depth_];  // emplace_back may have moved it
      if (depth_ == 0) fine.AP = A * fine.P;
      else fine.AP = fine.A * fine.P;
      coarse.A = fine.R * fine.AP;
      coarse.b.resize(coarse.A.rows());
      vertices = &fine.coarse_vertices;
      nx = nx / 2 + 1;
      ny = ny / 2 + 1;
      ++depth_;
    }
    Level& last = levels_[depth_];
    if (depth_ == 0) coarsest_matrix_ = A;
    else coarsest_matrix_ = last.A;
    coarsest_.compute(coarsest_matrix_);
    info_ = coarsest_.info();
    m_isInitialized = true;
    return *this;
  }

  Eigen::Index rows() const { return fine_ ? fine_->rows() : 0; }
  Eigen::Index cols() const { return rows(); }
  Eigen::ComputationInfo info() const { return info_; }
  int levels() const { return depth_ + 1; }
  int unknowns(int level) const { return levels_[level].n; }

  // x = M^-1 b: one V-cycle from x = 0.
  template <class Rhs, class Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    Level& top = levels_[0];
    top.b = b;
    cycle(0, top.b.data(), top.x.data());
    x = top.x;
  }

 private:
  struct Level {
    int n = 0;
    Matrix A;                 // this level's operator (level 0's is the caller's)
    Matrix P, R, AP;          // prolongation to this level from the next, R = P^T, A P
    std::vector<int> coarse_vertices;  // the next level's unknowns, as vertices of its grid
    std::vector<int> position;         // coarse vertex -> its unknown index, -1 if none
    Eigen::VectorXd inverse_diagonal, x, r, b;
  };

  // The next level's unknowns and P, R; false when coarsening would not shrink the level.
  bool coarsen(Level& level, int nx, int ny, const std::vector<int>& vertices) {
    const int cx = nx / 2 + 1, cy = ny / 2 + 1;
    level.position.assign(std::size_t(cx) * cy, -1);
    for (int K : vertices) level.position[(K / ny / 2) * cy + (K % ny) / 2] = 0;
    level.coarse_vertices.clear();
    for (int C = 0; C < cx * cy; ++C)
      if (level.position[C] == 0) {
        level.position[C] = static_cast<int>(level.coarse_vertices.size());
        level.coarse_vertices.push_back(C);
      }
    const int nc = static_cast<int>(level.coarse_vertices.size());
    if (4 * nc > 3 * level.n) return false;
    Matrix& P = level.P;
    P.resize(level.n, nc);
    P.reserve(Eigen::VectorXi::Constant(level.n, 4));
    for (int k = 0; k < level.n; ++k) {
      const int a = vertices[k] / ny, b = vertices[k] % ny;
      // Bilinear weights: an even vertex is a coarse one, an odd one halfway between two.
      const int c0 = a / 2, c1 = (a + 1) / 2, d0 = b / 2, d1 = (b + 1) / 2;
      const double wx = c0 == c1 ? 1.0 : 0.5, wy = d0 == d1 ? 1.0 : 0.5;
      for (int c = c0; c <= c1; ++c)
        for (int d = d0; d <= d1; ++d) {
          const int l = level.position[c * cy + d];
          if (l >= 0) P.insert(k, l) = wx * wy;
        }
    }
    P.makeCompressed();
    level.R = P.transpose();
    return true;
  }

  // Gauss-Seidel in A's row order (forward) or against it.
  template <class M>
  static void sweep(const M& A, const Eigen::VectorXd& inverse_diagonal, const double* b, double* x,
                    bool forward) {
    const int n = static_cast<int>(A.rows());
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    const double* value = A.valuePtr();
    for (int s = 0; s < n; ++s) {
      const int i = forward ? s : n - 1 - s;
      double sum = b[i];
      for (int e = outer[i]; e < outer[i + 1]; ++e)
        if (inner[e] != i) sum -= value[e] * x[inner[e]];
      x[i] = sum * inverse_diagonal[i];
    }
  }

  void cycle(int l, const double* b, double* x) const {
    Level& level = levels_[l];
    const int n = level.n;
    if (l == depth_) {
      Eigen::Map<Eigen::VectorXd>(x, n) = coarsest_.solve(Eigen::Map<const Eigen::VectorXd>(b, n));
      return;
    }
    std::fill(x, x + n, 0.0);
    if (l == 0) smooth_and_correct(*fine_, level, l, b, x);
    else smooth_and_correct(level.A, level, l, b, x);
  }

  template <class M>
  void smooth_and_correct(const M& A, Level& level, int l, const double* b, double* x) const {
    const int n = level.n;
    sweep(A, level.inverse_diagonal, b, x, true);
    Eigen::Map<Eigen::VectorXd> xv(x, n);
    level.r.noalias() = A * xv;
    level.r = Eigen::Map<const Eigen::VectorXd>(b, n) - level.r;
    Level& coarse = levels_[l + 1];
    coarse.b.noalias() = level.R * level.r;
    cycle(l + 1, coarse.b.data(), coarse.x.data());
    xv.noalias() += level.P * coarse.x;
    sweep(A, level.inverse_diagonal, b, x, false);
  }

  int coarsest_size_ = 400;
  int nx_ = 0, ny_ = 0;
  const std::vector<int>* vertices_ = nullptr;
  using FineMatrix = Eigen::Map<const Matrix>;
  std::optional<FineMatrix> fine_;
  mutable std::vector<Level> levels_;
  int depth_ = 0;
  Eigen::SparseMatrix<double> coarsest_matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarsest_;
  Eigen::ComputationInfo info_ = Eigen::Success;
};

}  // namespace bsmpm

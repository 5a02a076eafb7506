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
// symmetric positive definite operator: a preconditioner conjugate gradients accept.
//
// Thin water (set_thin_rows): a sheet or a ligament one to three vertices thick, and a drop
// of spray, carries an alternating pressure mode A barely sees (the vertex checkerboard the
// stabilization does not reach, as it needs three unknowns in a line), which neither the
// point smoother (it is not diagonally dominant) nor the bilinear coarse space reduces: after
// the Lobovsky impact the V-cycle's CG took 27-47 iterations where these were the slowest
// modes. The fine level's unknowns whose rows are short (at most three grid lines of a full
// row's) are therefore solved together exactly (sparse LDL^T of A restricted to them) after
// the forward sweep and before the backward one: a block of the symmetric smoother, so the
// cycle stays symmetric positive definite.
//
// From
// x = 0 the forward sweep reads only the strictly lower triangle (in its order) and leaves the residual
// -U x (U the strictly upper triangle), so sweep and residual cost one pass over A. The
// sweeps take the unknowns in strips of vertex columns wider than a row's reach, the even
// strips first, then the odd ones (Gauss-Seidel in that fixed order, so the cycle stays
// symmetric): the strips of one parity do not couple and are swept side by side. The
// Galerkin products and the transfers go by rows. Each value is summed by one thread in a
// fixed order: the same bits for any thread count. The levels are compressed-row arrays that
// keep their storage from step to step (the Galerkin products by a dense accumulator per
// row, no allocation once the water stops growing).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace bsmpm {

class MultigridPreconditioner : public Eigen::SparseSolverBase<MultigridPreconditioner> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  // A level of at most this many unknowns is solved exactly (default 400).
  void set_coarsest(int unknowns) { coarsest_size_ = unknowns; }

  // The fine level's unknowns whose rows hold at most this many entries are thin (solved
  // together exactly in the smoother); 0: none.
  void set_thin_rows(int entries) { thin_rows_ = entries; }
  int thin_unknowns() const { return levels_.empty() ? 0 : static_cast<int>(levels_[0].thin.size()); }

  // How many vertices along a grid line a row of the finest level reaches at most (the
  // coarser levels' rows reach no further): the smoother's strips are wider.
  void set_reach(int vertices) { reach_ = vertices; }

  // The unknowns' vertices K = a * ny + b on the nx x ny vertex grid, in A's order; set
  // before compute().
  void set_vertices(int nx, int ny, const std::vector<int>& unknowns) {
    nx_ = nx;
    ny_ = ny;
    vertices_ = &unknowns;
  }

  // A compressed row-major sparse matrix with sorted rows (or a Ref to one, as
  // ConjugateGradient passes it); it must outlive the solve, which reads it in place.
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
    static_assert(M::IsRowMajor, "the multigrid reads A by rows");
    eigen_assert(matrix.isCompressed());
    fine_ = Csr{static_cast<int>(matrix.rows()), matrix.outerIndexPtr(), matrix.innerIndexPtr(), matrix.valuePtr()};
    depth_ = 0;
    int nx = nx_, ny = ny_;
    const std::vector<int>* vertices = vertices_;
    for (;;) {
      if (depth_ == static_cast<int>(levels_.size())) levels_.emplace_back();
      Level& level = levels_[depth_];
      const Csr A = matrix_of(depth_);
      level.n = A.rows;
      level.inverse_diagonal.resize(level.n);
#pragma omp parallel for schedule(static) if (level.n > kParallelRows)
      for (int i = 0; i < level.n; ++i) {
        double d = 0.0;
        for (int e = A.outer[i]; e < A.outer[i + 1]; ++e)
          if (A.inner[e] == i) d = A.value[e];
        level.inverse_diagonal[i] = d > 0.0 ? 1.0 / d : 0.0;
      }
      if (depth_ == 0) set_thin(level, A);
      set_strips(level, nx, ny, *vertices);
      level.x.resize(level.n);
      level.r.resize(level.n);
      level.b.resize(level.n);
      const bool stop = level.n <= coarsest_size_ || nx <= 2 || ny <= 2 || !coarsen(level, nx, ny, *vertices);
      if (stop) break;
      if (depth_ + 1 == static_cast<int>(levels_.size())) levels_.emplace_back();
      Level& fine = levels_[depth_];  // emplace_back may have moved it
      Level& coarse = levels_[depth_ + 1];
      const int nc = static_cast<int>(fine.coarse_vertices.size());
      multiply(A, fine.P.view(), nc, fine.AP);               // A P
      multiply(fine.R.view(), fine.AP.view(), nc, coarse.A);  // P^T (A P)
      vertices = &fine.coarse_vertices;
      nx = nx / 2 + 1;
      ny = ny / 2 + 1;
      ++depth_;
    }
    // The coarsest level exactly: a row-major symmetric matrix read as column-major is itself.
    const Csr last = matrix_of(depth_);
    coarsest_matrix_ = Eigen::Map<const Eigen::SparseMatrix<double>>(last.rows, last.rows, last.outer[last.rows],
                                                                      last.outer, last.inner, last.value);
    // A coarse unknown whose finer rows are all empty (water whose control points the walls or
    // the mass cut-off all hold) has an empty row: a relative shift of 1e-10 keeps its pivot
    // finite (measured on the jet on a wall: without it, 17 solves in 670 fell back to Jacobi,
    // one with a NaN; with it none).
    double largest = 0.0;
    for (int i = 0; i < last.rows; ++i)
      for (int e = last.outer[i]; e < last.outer[i + 1]; ++e)
        if (last.inner[e] == i) largest = std::max(largest, last.value[e]);
    coarsest_.setShift(1e-10 * largest);
    coarsest_.compute(coarsest_matrix_);
    info_ = coarsest_.info();
    m_isInitialized = true;
    return *this;
  }

  Eigen::Index rows() const { return fine_.rows; }
  Eigen::Index cols() const { return fine_.rows; }
  Eigen::ComputationInfo info() const { return info_; }
  int levels() const { return depth_ + 1; }
  int unknowns(int level) const { return levels_[level].n; }

  // x = M^-1 b: one V-cycle from x = 0.
  template <class Rhs, class Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    Level& top = levels_[0];
    top.b = b;
    cycle(0);
    x = top.x;
  }

 private:
  // A compressed-row view (sorted rows).
  struct Csr {
    int rows = 0;
    const int* outer = nullptr;
    const int* inner = nullptr;
    const double* value = nullptr;
  };
  struct Storage {
    std::vector<int> outer, inner;
    std::vector<double> value;
    Csr view() const { return Csr{static_cast<int>(outer.size()) - 1, outer.data(), inner.data(), value.data()}; }
  };
  struct Level {
    int n = 0;
    Storage A;                         // this level's operator (level 0's is the caller's)
    Storage P, R, AP;                  // prolongation from the next level, R = P^T, and A P
    std::vector<int> coarse_vertices;  // the next level's unknowns, as vertices of its grid
    std::vector<int> position;         // coarse vertex -> its unknown index, -1 if none
    // The smoother's order (set_strips): [strips[s], strips[s + 1]) the unknowns of the s-th
    // non-empty strip of vertex columns; coloured[c] the strips whose number has parity c.
    std::vector<int> strips;
    std::vector<std::vector<int>> coloured;  // per colour: the strips (indices into strips)
    Eigen::VectorXd inverse_diagonal, x, r, b;
    // The thin unknowns (level 0): their indices, A restricted to them and its factor.
    std::vector<int> thin;
    Eigen::SparseMatrix<double> thin_matrix;
    std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> thin_factor;
    Eigen::VectorXd thin_r, thin_x;
  };

  Csr matrix_of(int l) const { return l == 0 ? fine_ : levels_[l].A.view(); }

  // C = A B (rows of A, columns 0..cols-1 of B), each row gathered in a dense accumulator
  // in A's and B's order, then written in column order. Each row is its own sum, so the
  // chunks of rows, computed side by side, give the same bits for any thread count.
  void multiply(const Csr& A, const Csr& B, int cols, Storage& C) {
    const int rows = A.rows;
    const int count = rows > kParallelRows ? kChunks : 1;
    if (static_cast<int>(chunks_.size()) < count) chunks_.resize(count);
#pragma omp parallel for schedule(dynamic, 1) if (count > 1)
    for (int c = 0; c < count; ++c) {
      Chunk& chunk = chunks_[c];
      if (static_cast<int>(chunk.accumulator.size()) < cols) {
        chunk.accumulator.assign(cols, 0.0);
        chunk.touched.assign(cols, 0);
      }
      chunk.inner.clear();
      chunk.value.clear();
      chunk.length.clear();
      std::vector<int>& columns = chunk.columns;
      double* const accumulator = chunk.accumulator.data();
      char* const touched = chunk.touched.data();
      for (int i = static_cast<int>(std::int64_t(rows) * c / count); i < std::int64_t(rows) * (c + 1) / count; ++i) {
        columns.clear();
        for (int e = A.outer[i]; e < A.outer[i + 1]; ++e) {
          const int k = A.inner[e];
          const double a = A.value[e];
          for (int f = B.outer[k]; f < B.outer[k + 1]; ++f) {
            const int j = B.inner[f];
            if (!touched[j]) {
              touched[j] = 1;
              columns.push_back(j);
            }
            accumulator[j] += a * B.value[f];
          }
        }
        std::sort(columns.begin(), columns.end());
        for (int j : columns) {
          chunk.inner.push_back(j);
          chunk.value.push_back(accumulator[j]);
          accumulator[j] = 0.0;
          touched[j] = 0;
        }
        chunk.length.push_back(static_cast<int>(columns.size()));
      }
    }
    C.outer.resize(rows + 1);
    C.outer[0] = 0;
    std::vector<int>& start = chunk_start_;
    start.resize(count);
    for (int c = 0, i = 0; c < count; ++c) {
      start[c] = C.outer[i];
      for (int length : chunks_[c].length) {
        C.outer[i + 1] = C.outer[i] + length;
        ++i;
      }
    }
    C.inner.resize(C.outer[rows]);
    C.value.resize(C.outer[rows]);
#pragma omp parallel for schedule(static) if (count > 1)
    for (int c = 0; c < count; ++c) {
      std::copy(chunks_[c].inner.begin(), chunks_[c].inner.end(), C.inner.begin() + start[c]);
      std::copy(chunks_[c].value.begin(), chunks_[c].value.end(), C.value.begin() + start[c]);
    }
  }

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
    Storage& P = level.P;
    P.outer.assign(1, 0);
    P.inner.clear();
    P.value.clear();
    for (int k = 0; k < level.n; ++k) {
      const int a = vertices[k] / ny, b = vertices[k] % ny;
      // Bilinear weights: an even vertex is a coarse one, an odd one halfway between two.
      const int c0 = a / 2, c1 = (a + 1) / 2, d0 = b / 2, d1 = (b + 1) / 2;
      const double wx = c0 == c1 ? 1.0 : 0.5, wy = d0 == d1 ? 1.0 : 0.5;
      for (int c = c0; c <= c1; ++c)
        for (int d = d0; d <= d1; ++d) {
          const int l = level.position[c * cy + d];
          if (l >= 0) {
            P.inner.push_back(l);
            P.value.push_back(wx * wy);
          }
        }
      P.outer.push_back(static_cast<int>(P.inner.size()));
    }
    // R = P^T by counting: the rows of P in order, so each row of R comes out sorted.
    Storage& R = level.R;
    R.outer.assign(nc + 1, 0);
    for (int j : P.inner) ++R.outer[j + 1];
    for (int c = 0; c < nc; ++c) R.outer[c + 1] += R.outer[c];
    R.inner.resize(P.inner.size());
    R.value.resize(P.value.size());
    next_.assign(R.outer.begin(), R.outer.end() - 1);
    for (int k = 0; k < level.n; ++k)
      for (int e = P.outer[k]; e < P.outer[k + 1]; ++e) {
        const int at = next_[P.inner[e]]++;
        R.inner[at] = k;
        R.value[at] = P.value[e];
      }
    return true;
  }

  // The thin unknowns of `level` (rows of at most thin_rows_ entries) and their block's factor.
  void set_thin(Level& level, const Csr& A) {
    level.thin.clear();
    for (int i = 0; i < level.n; ++i)
      if (A.outer[i + 1] - A.outer[i] <= thin_rows_) level.thin.push_back(i);
    const int m = static_cast<int>(level.thin.size());
    if (m == 0) return;
    thin_position_.assign(level.n, -1);
    for (int t = 0; t < m; ++t) thin_position_[level.thin[t]] = t;
    // Column-major with sorted columns: the rows of a symmetric block, read as its columns.
    Eigen::SparseMatrix<double>& B = level.thin_matrix;
    B.resize(m, m);
    B.resizeNonZeros(0);
    thin_outer_.assign(1, 0);
    thin_inner_.clear();
    thin_value_.clear();
    double largest = 0.0;
    for (int t = 0; t < m; ++t) {
      const int i = level.thin[t];
      for (int e = A.outer[i]; e < A.outer[i + 1]; ++e) {
        const int u = thin_position_[A.inner[e]];
        if (u < 0) continue;
        thin_inner_.push_back(u);
        thin_value_.push_back(A.value[e]);
        if (u == t) largest = std::max(largest, A.value[e]);
      }
      thin_outer_.push_back(static_cast<int>(thin_inner_.size()));
    }
    B = Eigen::Map<const Eigen::SparseMatrix<double>>(m, m, thin_outer_.back(), thin_outer_.data(), thin_inner_.data(),
                                                      thin_value_.data());
    if (!level.thin_factor) level.thin_factor = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>();
    // A drop's block can be singular but for round-off (its constant or alternating mode): the
    // coarsest level's relative shift keeps the pivots finite.
    level.thin_factor->setShift(1e-10 * largest);
    level.thin_factor->compute(B);
    level.thin_r.resize(m);
  }

  // The thin block of the smoother, given thin_r = (b - A x) on the thin unknowns: x_T +=
  // A_TT^-1 thin_r; and, when r is given, r -= A x_T's change on every row (A symmetric:
  // row t of A scattered).
  void solve_thin(Level& level, const Csr& A, double* x, double* r) const {
    level.thin_x = level.thin_factor->solve(level.thin_r);
    const int m = static_cast<int>(level.thin.size());
    for (int t = 0; t < m; ++t) {
      const int i = level.thin[t];
      const double dx = level.thin_x[t];
      x[i] += dx;
      if (r)
        for (int e = A.outer[i]; e < A.outer[i + 1]; ++e) r[A.inner[e]] -= A.value[e] * dx;
    }
  }

  // The strips of `level` (its unknowns' vertices on the nx x ny grid, in vertex order):
  // columns [s W, (s + 1) W) with W = max(reach + 1, nx / kStrips), numbered s; the
  // non-empty ones listed per parity of s. Strips of one parity lie at least W columns apart,
  // beyond any row's reach, so the smoother sweeps them side by side (a fixed order: Gauss-
  // Seidel in the order even strips, then odd strips, each by columns; the same bits for any
  // thread count).
  void set_strips(Level& level, int nx, int ny, const std::vector<int>& vertices) const {
    const int width = std::max(reach_ + 1, nx / kStrips);
    level.strips.clear();
    level.coloured.assign(2, {});
    int last = -1;
    for (int k = 0; k < level.n; ++k) {
      const int strip = vertices[k] / ny / width;
      if (strip == last) continue;
      level.coloured[strip % 2].push_back(static_cast<int>(level.strips.size()));
      level.strips.push_back(k);
      last = strip;
    }
    level.strips.push_back(level.n);
  }

  // Calls f(begin, end) for every strip of `colour` of `level`, side by side when it is large.
  template <class F>
  static void for_strips(const Level& level, int colour, F&& f) {
    const std::vector<int>& list = level.coloured[colour];
    const int count = static_cast<int>(list.size());
#pragma omp parallel for schedule(dynamic, 1) if (level.n > kParallelRows)
    for (int t = 0; t < count; ++t) f(level.strips[list[t]], level.strips[list[t] + 1]);
  }

  // One V-cycle on level l from x = 0: levels_[l].x = M_l^-1 levels_[l].b.
  void cycle(int l) const {
    Level& level = levels_[l];
    const int n = level.n;
    double* const x = level.x.data();
    const double* const b = level.b.data();
    if (l == depth_) {
      level.x = coarsest_.solve(level.b);
      return;
    }
    const Csr A = matrix_of(l);
    const double* const inverse_diagonal = level.inverse_diagonal.data();
    // Forward Gauss-Seidel from x = 0 in the strips' order: the even strips (reading only
    // their own unknowns before i), then the odd ones (reading everything but their own
    // unknowns after i, still zero).
    for_strips(level, 0, [&](int s, int end) {
      for (int i = s; i < end; ++i) {
        double sum = b[i];
        int e = A.outer[i];
        while (e < A.outer[i + 1] && A.inner[e] < s) ++e;
        for (; e < A.outer[i + 1] && A.inner[e] < i; ++e) sum -= A.value[e] * x[A.inner[e]];
        x[i] = sum * inverse_diagonal[i];
      }
    });
    for_strips(level, 1, [&](int s, int end) {
      for (int i = s; i < end; ++i) {
        double sum = b[i];
        for (int e = A.outer[i]; e < A.outer[i + 1] && A.inner[e] < i; ++e) sum -= A.value[e] * x[A.inner[e]];
        for (int e = A.outer[i + 1] - 1; e >= A.outer[i] && A.inner[e] >= end; --e) sum -= A.value[e] * x[A.inner[e]];
        x[i] = sum * inverse_diagonal[i];
      }
    });
    // r = b - A x: what each row's update did not yet see (an even row: the unknowns before
    // its strip and those after it; an odd row: its strip's unknowns after it).
    double* const r = level.r.data();
    for_strips(level, 0, [&](int s, int end) {
      for (int i = s; i < end; ++i) {
        double sum = 0.0;
        for (int e = A.outer[i]; e < A.outer[i + 1] && A.inner[e] < s; ++e) sum -= A.value[e] * x[A.inner[e]];
        for (int e = A.outer[i + 1] - 1; e >= A.outer[i] && A.inner[e] > i; --e) sum -= A.value[e] * x[A.inner[e]];
        r[i] = sum;
      }
    });
    for_strips(level, 1, [&](int s, int end) {
      for (int i = s; i < end; ++i) {
        double sum = 0.0;
        for (int e = A.outer[i + 1] - 1; e >= A.outer[i] && A.inner[e] > i; --e)
          if (A.inner[e] < end) sum -= A.value[e] * x[A.inner[e]];
        r[i] = sum;
      }
    });
    if (!level.thin.empty()) {  // the thin block: x_T += A_TT^-1 r_T, r updated
      for (std::size_t t = 0; t < level.thin.size(); ++t) level.thin_r[t] = r[level.thin[t]];
      solve_thin(level, A, x, r);
    }
    // The coarse correction: b_c = R r, x += P x_c.
    Level& coarse = levels_[l + 1];
    const Csr R = level.R.view(), P = level.P.view();
#pragma omp parallel for schedule(static) if (n > kParallelRows)
    for (int c = 0; c < coarse.n; ++c) {
      double sum = 0.0;
      for (int e = R.outer[c]; e < R.outer[c + 1]; ++e) sum += R.value[e] * r[R.inner[e]];
      coarse.b[c] = sum;
    }
    cycle(l + 1);
    const double* const xc = coarse.x.data();
#pragma omp parallel for schedule(static) if (n > kParallelRows)
    for (int i = 0; i < n; ++i)
      for (int e = P.outer[i]; e < P.outer[i + 1]; ++e) x[i] += P.value[e] * xc[P.inner[e]];
    if (!level.thin.empty()) {  // the thin block again (the adjoint order): x_T += A_TT^-1 (b - A x)_T
      for (std::size_t t = 0; t < level.thin.size(); ++t) {
        const int i = level.thin[t];
        double sum = b[i];
        for (int e = A.outer[i]; e < A.outer[i + 1]; ++e) sum -= A.value[e] * x[A.inner[e]];
        level.thin_r[t] = sum;
      }
      solve_thin(level, A, x, nullptr);
    }
    // Backward Gauss-Seidel: the forward sweep's order reversed (the odd strips, then the
    // even ones, each from its last unknown).
    for (int colour = 1; colour >= 0; --colour)
      for_strips(level, colour, [&](int s, int end) {
        for (int i = end - 1; i >= s; --i) {
          double sum = b[i];
          for (int e = A.outer[i]; e < A.outer[i + 1]; ++e)
            if (A.inner[e] != i) sum -= A.value[e] * x[A.inner[e]];
          x[i] = sum * inverse_diagonal[i];
        }
      });
  }

  static constexpr int kParallelRows = 4096;  // a level's loops run side by side above this many unknowns
  static constexpr int kStrips = 64;          // about this many strips across the grid
  int coarsest_size_ = 400;
  int reach_ = 3;
  int thin_rows_ = 0;
  std::vector<int> thin_position_, thin_outer_, thin_inner_;
  std::vector<double> thin_value_;
  int nx_ = 0, ny_ = 0;
  const std::vector<int>* vertices_ = nullptr;
  Csr fine_;
  mutable std::vector<Level> levels_;
  int depth_ = 0;
  // multiply's rows in chunks: each its accumulator (zero between rows) and its output.
  struct Chunk {
    std::vector<double> accumulator, value;
    std::vector<char> touched;
    std::vector<int> columns, inner, length;
  };
  static constexpr int kChunks = 16;
  std::vector<Chunk> chunks_;
  std::vector<int> chunk_start_, next_;
  Eigen::SparseMatrix<double> coarsest_matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarsest_;
  Eigen::ComputationInfo info_ = Eigen::Success;
};

}  // namespace bsmpm

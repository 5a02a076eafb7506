// The discrete divergence of the incompressible fluid (docs/method.md §12, eq. I2): between
// the pressure hats Q_K (pressure_grid.hpp) and the velocity's B-splines S_I,
//
//   D_KI = sum_p V_p Q_K(x_p) grad S_I(x_p)      (a vector per pair),
//
// integrated with the particles, so that (D v)_K = sum_p V_p Q_K(x_p) div v(x_p) is the
// water's own divergence around vertex K and (D^T p)_I = sum_p V_p p(x_p) grad S_I(x_p) is
// the internal force of eq. 7 for sigma = -p I: the projection's pressure force and the
// explicit step's are one operator. Stored per vertex on the structured grid: a vertex
// couples to the (P + 2) x (P + 2) control points whose support overlaps its hat's.
// Besides D, the same scatter gathers per vertex the particle volume sum_p V_p Q_K (the
// volume fraction), the excess volume sum_p V0_p Q_K (J_p - 1) (the volume correction) and
// sum_p V_p Q_K p_p (the warm start of the solve).
#pragma once

#include <algorithm>
#include <vector>

#include "grid/grid.hpp"
#include "step/incompressible/pressure_grid.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class DivergenceOperator {
 public:
  static constexpr int kSpan = P + 2;  // control points per axis a hat couples to: offsets -1 .. P
  static constexpr int kEntries = kSpan * kSpan;

  struct Moments {
    double volume = 0.0;    // sum_p V_p Q_K
    double volume0 = 0.0;   // sum_p V0_p Q_K: how much water the hat holds, whatever its J
    double excess = 0.0;    // sum_p V0_p (J_p - 1) Q_K
    double pressure = 0.0;  // sum_p V_p p_p Q_K
  };

  void resize(const PressureGrid& grid, int node_nx, int node_ny) {
    grid_ = grid;
    node_nx_ = node_nx;
    node_ny_ = node_ny;
    entries_.assign(std::size_t(grid.count()) * kEntries, Vec2::Zero());
    moments_.assign(grid.count(), Moments{});
  }
  const PressureGrid& grid() const { return grid_; }
  std::size_t bytes() const { return heap_bytes(entries_) + heap_bytes(moments_); }

  // Zeroes the vertices of `box` (vertex indices) for the next step.
  void clear(const NodeBox& box) {
    const int ny = grid_.ny();
#pragma omp parallel for schedule(static) if ((box.i1 - box.i0) * (box.j1 - box.j0) > 4096)
    for (int a = box.i0; a < box.i1; ++a) {
      std::fill_n(entries_.begin() + (std::size_t(a) * ny + box.j0) * kEntries, std::size_t(box.j1 - box.j0) * kEntries,
                  Vec2::Zero());
      std::fill_n(moments_.begin() + a * ny + box.j0, box.j1 - box.j0, Moments{});
    }
  }

  // One particle's share (eq. I2). The caller scatters in a strip order: a particle writes
  // the vertex columns of its cell's corners, within the columns its control points span.
  void add_particle(const ParticleWeights<P>& w, const PressureGrid::Hats& q, double V, double V0, double excess,
                    double pressure) {
    const int ny = grid_.ny();
    for (int ha = 0; ha < 2; ++ha)
      for (int hb = 0; hb < 2; ++hb) {
        const int K = (w.i0 + ha) * ny + w.j0 + hb;
        const double s = q.qx[ha] * q.qy[hb];
        Moments& m = moments_[K];
        m.volume += s * V;
        m.volume0 += s * V0;
        m.excess += s * excess;
        m.pressure += s * V * pressure;
        Vec2* const row = entries_.data() + std::size_t(K) * kEntries;
        const double sv = s * V;
        for (int e = 0; e <= P; ++e) {
          const int oe = (e - ha + 1) * kSpan - hb + 1;  // offset of control point (i0 + e, j0 + f): (e - ha + 1, f - hb + 1)
          const double gx = sv * w.gx[e], wx = sv * w.wx[e];
          for (int f = 0; f <= P; ++f) row[oe + f] += Vec2(gx * w.wy[f], wx * w.gy[f]);
        }
      }
  }

  const Moments& moments(int K) const { return moments_[K]; }
  // The coupling of vertex K to the control point at offset (e, f) from it, i.e. control
  // point (a - 1 + e, b - 1 + f) for K = (a, b).
  const Vec2* row(int K) const { return entries_.data() + std::size_t(K) * kEntries; }

  // (D^T x)_I for the control point I = (i, j): sum over the vertices whose hats overlap it.
  Vec2 transpose_at(const std::vector<double>& x, int i, int j) const {
    const int ny = grid_.ny();
    Vec2 t = Vec2::Zero();
    for (int e = 0; e < kSpan; ++e) {
      const int a = i + 1 - e;
      if (a < 0 || a > grid_.cells_x) continue;
      for (int f = 0; f < kSpan; ++f) {
        const int b = j + 1 - f;
        if (b < 0 || b > grid_.cells_y) continue;
        const int K = a * ny + b;
        if (x[K] != 0.0) t += x[K] * entries_[std::size_t(K) * kEntries + e * kSpan + f];
      }
    }
    return t;
  }

  // Calls visit(D_KI, I) for every control point I on the grid that vertex K couples to, in
  // the row's order (the order every sum over a row takes).
  template <class Visit>
  void for_each_in_row(int K, Visit&& visit) const {
    const int a = K / grid_.ny(), b = K % grid_.ny();
    const Vec2* const r = row(K);
    for (int e = 0; e < kSpan; ++e) {
      const int i = a - 1 + e;
      if (i < 0 || i >= node_nx_) continue;
      for (int f = 0; f < kSpan; ++f) {
        const int j = b - 1 + f;
        if (j < 0 || j >= node_ny_) continue;
        visit(r[e * kSpan + f], i * node_ny_ + j);
      }
    }
  }

  // (D t)_K = sum_I D_KI . t_I over the control points vertex K couples to.
  double row_times(int K, const std::vector<Vec2>& t) const {
    double sum = 0.0;
    for_each_in_row(K, [&](const Vec2& d, int I) { sum += d.dot(t[I]); });
    return sum;
  }

 private:
  PressureGrid grid_;
  int node_nx_ = 0, node_ny_ = 0;
  std::vector<Vec2> entries_;
  std::vector<Moments> moments_;
};

}  // namespace bsmpm

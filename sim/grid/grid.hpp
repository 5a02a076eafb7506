// The tensor-product control-point grid: one clamped B-spline basis per axis, control
// points indexed (i, j) -> i * ny + j, placed at their Greville abscissae.
#pragma once

#include <algorithm>
#include <vector>

#include "bspline/clamped_bspline.hpp"
#include "core/types.hpp"

namespace bsmpm {

// Rectangle of control-point indices [i0, i1) x [j0, j1); empty when i0 >= i1.
struct NodeBox {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  bool empty() const { return i0 >= i1 || j0 >= j1; }
  void include(const NodeBox& o) {
    if (o.empty()) return;
    if (empty()) { *this = o; return; }
    i0 = std::min(i0, o.i0); i1 = std::max(i1, o.i1);
    j0 = std::min(j0, o.j0); j1 = std::max(j1, o.j1);
  }
};

template <int P>
struct Grid {
  using Basis = ClampedBSpline<P>;
  Basis bx, by;

  Grid() = default;
  Grid(Vec2 origin, Vec2 cell_size, int cells_x, int cells_y)
      : bx(origin.x(), cell_size.x(), cells_x), by(origin.y(), cell_size.y(), cells_y) {
    for (int i = 0; i < nx(); ++i) greville_x_.push_back(bx.greville(i));
    for (int j = 0; j < ny(); ++j) greville_y_.push_back(by.greville(j));
  }

  int nx() const { return bx.basis_count(); }
  int ny() const { return by.basis_count(); }
  int node_count() const { return nx() * ny(); }
  int index(int i, int j) const { return i * ny() + j; }
  Vec2 greville(int i, int j) const { return {greville_x_[i], greville_y_[j]}; }
  // The control points' abscissae per axis, xi_i and eta_j (the transfers read them per particle).
  const double* greville_x() const { return greville_x_.data(); }
  const double* greville_y() const { return greville_y_.data(); }
  Vec2 origin() const { return {bx.origin(), by.origin()}; }
  Vec2 extent_max() const { return {bx.end(), by.end()}; }
  Vec2 cell_size() const { return {bx.cell_size(), by.cell_size()}; }

 private:
  std::vector<double> greville_x_, greville_y_;
};

// One velocity field on the grid: a body, or a group of bodies sharing a field.
// All arrays are zero between steps outside the nodes the step touched.
struct GridLayer {
  std::vector<double> mass;
  std::vector<Vec2> momentum;           // eq. 6 numerator: v_I^k = momentum / mass
  std::vector<Vec2> force;              // eqs. 7-8
  std::vector<Vec2> velocity;           // v_I^{k+1} after all constraints (eq. 10)
  std::vector<Vec2> velocity_increment; // v_I^{k+1} - v_I^k, the FLIP increment of eq. 11
  std::vector<Vec2> remap_velocity;     // eq. 13: remapped momentum, then velocity
  std::vector<Vec2> mass_gradient;      // sum_p m_p grad S_Ip: contact normals (contact only)
  std::vector<double> volume;           // sum_p V_p S_Ip: the volume fraction (particle shifting only)
  bool tracks_mass_gradient = false;
  bool tracks_volume = false;
  NodeBox active;                       // nodes written this step

  std::size_t bytes() const {
    return heap_bytes(mass) + heap_bytes(momentum) + heap_bytes(force) + heap_bytes(velocity) +
           heap_bytes(velocity_increment) + heap_bytes(remap_velocity) + heap_bytes(mass_gradient) +
           heap_bytes(volume);
  }
  void resize(int n) {
    mass.assign(n, 0.0);
    momentum.assign(n, Vec2::Zero());
    force.assign(n, Vec2::Zero());
    velocity.assign(n, Vec2::Zero());
    velocity_increment.assign(n, Vec2::Zero());
    remap_velocity.assign(n, Vec2::Zero());
    if (tracks_mass_gradient) mass_gradient.assign(n, Vec2::Zero());
    if (tracks_volume) volume.assign(n, 0.0);
  }
};

}  // namespace bsmpm

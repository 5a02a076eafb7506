// Where the pressure of the incompressible fluid lives (docs/method.md §12): the clamped
// linear B-splines on the velocity's knots, one degree below the velocity's, i.e. the hat
// functions Q_K of the cell corners ("vertices", (cells_x + 1) x (cells_y + 1) of them,
// indexed K = a * (cells_y + 1) + b like the control points). A particle in cell (c, d)
// sees the four hats of that cell's corners, Q_K(x) = q_a(x) q_b(y).
#pragma once

#include <array>
#include <vector>

#include "core/types.hpp"
#include "grid/grid.hpp"

namespace bsmpm {

struct PressureGrid {
  int cells_x = 0, cells_y = 0;
  Vec2 origin = Vec2::Zero();
  Vec2 cell_size = Vec2::Ones();

  PressureGrid() = default;
  template <int P>
  explicit PressureGrid(const Grid<P>& grid)
      : cells_x(grid.bx.cells()), cells_y(grid.by.cells()), origin(grid.origin()), cell_size(grid.cell_size()) {}

  int nx() const { return cells_x + 1; }
  int ny() const { return cells_y + 1; }
  int count() const { return nx() * ny(); }
  int index(int a, int b) const { return a * ny() + b; }

  // The two non-zero hats per axis at x in cell (c, d): q[0] of corner c, q[1] of corner c + 1.
  struct Hats {
    std::array<double, 2> qx, qy;
  };
  // `cell` is the particle's cell per axis (its first velocity control point, ParticleWeights).
  Hats at(const Vec2& x, int cell_x, int cell_y) const {
    const double tx = (x.x() - origin.x()) / cell_size.x() - cell_x;
    const double ty = (x.y() - origin.y()) / cell_size.y() - cell_y;
    return {{1.0 - tx, tx}, {1.0 - ty, ty}};
  }
  // sum_K Q_K(x) f_K over the four corners of the cell whose first corner is K (hats `q`).
  double interpolate(const Hats& q, const std::vector<double>& f, int K) const {
    const int vy = ny();
    return q.qx[0] * (q.qy[0] * f[K] + q.qy[1] * f[K + 1]) + q.qx[1] * (q.qy[0] * f[K + vy] + q.qy[1] * f[K + vy + 1]);
  }
  // The integral of Q_K over the domain: h_x h_y, halved per axis on a wall.
  double hat_integral(int a, int b) const {
    const double fx = (a == 0 || a == cells_x) ? 0.5 : 1.0, fy = (b == 0 || b == cells_y) ? 0.5 : 1.0;
    return fx * fy * cell_size.x() * cell_size.y();
  }
};

}  // namespace bsmpm

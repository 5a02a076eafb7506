// The volume fraction at the particles' own scale (docs/method.md §10, sub-cell shifting):
// bilinear hats on a lattice of nodes as far apart as the seeding's particles (h / 2 with two
// particles a cell). The grid's B-splines cannot see how the particles sit inside the cells:
// a pattern that repeats from cell to cell (columns bunched at the knots, as in the shallow
// water behind a dam break) is a sum of h-periodic lattices, each of which the splines'
// partition of unity fills evenly, so the grid's volume fraction, and the shifting of §10
// that follows it, read it as an even lattice. On the finer hats a column at a knot fills its
// node twice over and leaves the node between two knots empty, and the gradient pushes the
// column apart.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/types.hpp"
#include "grid/grid.hpp"

namespace bsmpm {

template <int P>
class SubcellVolume {
 public:
  SubcellVolume() = default;
  // spacing: the seeding lattice's; the nodes are h / r apart with r = round(h / spacing), so
  // that an even lattice of that spacing fills every node alike (walls included, below).
  SubcellVolume(const Grid<P>& grid, const Vec2& spacing) {
    for (int k = 0; k < 2; ++k) {
      const ClampedBSpline<P>& basis = k == 0 ? grid.bx : grid.by;
      Axis& a = axis_[k];
      a.ratio = std::max(1, static_cast<int>(std::lround(basis.cell_size() / spacing[k])));
      a.origin = basis.origin();
      a.nodes = basis.cells() * a.ratio + 1;
      a.inv_spacing = a.ratio / basis.cell_size();
      a.inverse_integral = lattice_fraction_inverse(a, spacing[k]);
    }
    volume_.assign(std::size_t(axis_[0].nodes) * axis_[1].nodes, 0.0);
  }

  // Adds the particle's volume V to the hats around x (call in the strips' order: a particle
  // in cell c writes the node columns r c .. r (c + 1), inside its strip).
  void add(const Vec2& x, double V) {
    const Hat hx = hat(axis_[0], x.x()), hy = hat(axis_[1], x.y());
    double* const at = volume_.data() + std::size_t(hx.node) * axis_[1].nodes + hy.node;
    const double lx = 1.0 - hx.frac, ly = 1.0 - hy.frac;
    at[0] += lx * ly * V;
    at[1] += lx * hy.frac * V;
    at[axis_[1].nodes] += hx.frac * ly * V;
    at[axis_[1].nodes + 1] += hx.frac * hy.frac * V;
  }

  // grad phi at x, phi_n = sum_p hat_n(x_p) V_p / integral(hat_n) (1 on the seeding lattice).
  Vec2 gradient(const Vec2& x) const {
    const Hat hx = hat(axis_[0], x.x()), hy = hat(axis_[1], x.y());
    const int ny = axis_[1].nodes;
    const double* const V = volume_.data() + std::size_t(hx.node) * ny + hy.node;
    const double* const ix = axis_[0].inverse_integral.data() + hx.node;
    const double* const iy = axis_[1].inverse_integral.data() + hy.node;
    const double p00 = V[0] * ix[0] * iy[0], p01 = V[1] * ix[0] * iy[1];
    const double p10 = V[ny] * ix[1] * iy[0], p11 = V[ny + 1] * ix[1] * iy[1];
    const double lx = 1.0 - hx.frac, ly = 1.0 - hy.frac;
    return {axis_[0].inv_spacing * (ly * (p10 - p00) + hy.frac * (p11 - p01)),
            axis_[1].inv_spacing * (lx * (p01 - p00) + hx.frac * (p11 - p10))};
  }

  // Zeroes the nodes of the cells in `box` (the box of cells the last scatter wrote).
  void clear(const NodeBox& box) {
    const int ny = axis_[1].nodes;
    const int i0 = std::clamp(box.i0 * axis_[0].ratio, 0, axis_[0].nodes);
    const int i1 = std::clamp(box.i1 * axis_[0].ratio + 1, 0, axis_[0].nodes);
    const int j0 = std::clamp(box.j0 * axis_[1].ratio, 0, ny);
    const int j1 = std::clamp(box.j1 * axis_[1].ratio + 1, 0, ny);
    if (i0 >= i1 || j0 >= j1) return;
    for (int i = i0; i < i1; ++i) std::fill_n(volume_.begin() + std::size_t(i) * ny + j0, j1 - j0, 0.0);
  }

  // The smaller node spacing, h / r.
  double spacing() const { return std::min(1.0 / axis_[0].inv_spacing, 1.0 / axis_[1].inv_spacing); }
  std::size_t bytes() const {
    return heap_bytes(volume_) + heap_bytes(axis_[0].inverse_integral) + heap_bytes(axis_[1].inverse_integral);
  }

 private:
  struct Axis {
    int ratio = 1, nodes = 0;
    double origin = 0.0, inv_spacing = 0.0;
    std::vector<double> inverse_integral;  // 1 / (sum_k hat_n(x_k) dx) over the seeding lattice
  };
  struct Hat {
    int node;     // the lower node
    double frac;  // the weight of the upper one
  };

  // Inlined, and floor() as a truncation of u held at 0 or above (the same node: a u below
  // 0 clamps to node 0 either way): out of line it cost a third of the drift's instructions.
  [[gnu::always_inline]] static Hat hat(const Axis& a, double x) {
    const double u = (x - a.origin) * a.inv_spacing;
    const int node = std::min(static_cast<int>(std::max(u, 0.0)), a.nodes - 2);
    return {node, std::clamp(u - node, 0.0, 1.0)};
  }

  // The same normalisation as the grid's volume fraction (particle_shifting.hpp): an even
  // lattice x_k = origin + (k + 1/2) dx reads 1 at every node, the walls' half hats included.
  static std::vector<double> lattice_fraction_inverse(const Axis& a, double dx) {
    std::vector<double> sum(a.nodes, 0.0);
    const double length = (a.nodes - 1) / a.inv_spacing;
    const int count = static_cast<int>(std::lround(length / dx));
    for (int k = 0; k < count; ++k) {
      const Hat h = hat(a, a.origin + (k + 0.5) * dx);
      sum[h.node] += (1.0 - h.frac) * dx;
      sum[h.node + 1] += h.frac * dx;
    }
    for (double& v : sum) v = v > 0.0 ? 1.0 / v : 0.0;
    return sum;
  }

  Axis axis_[2];
  std::vector<double> volume_;  // sum_p hat_n(x_p) V_p, node (n, m) at n * nodes_y + m
};

}  // namespace bsmpm

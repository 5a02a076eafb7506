// Fixed-radius neighbour search over a point cloud: a uniform grid of square cells (a cell
// list), so that the neighbours within r of a point lie in the ceil(r / cell) rings of cells
// around its own. Built in O(N) by a counting sort of the points into cells; a query visits
// about (2 ceil(r / cell) + 1)^2 cell areas' worth of candidates, read in sequence from a
// copy of the points sorted by cell (not from the caller's array in random order: that is
// most of a query's cost at a few hundred thousand points). Used at render time to shape
// the splats from each particle's neighbourhood (splat_shapes.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace bsmpm::render {

class NeighbourGrid {
 public:
  // Indexes `points` (kept by reference: they must outlive the grid) in cells of side `cell`
  // (the radius of the commonest query). Non-finite points are left out: they have and are
  // no neighbours.
  NeighbourGrid(const std::vector<Vec2>& points, double cell);

  // Calls f(j, offset) for every point j of the grid with |offset| < r, offset = points[j] - p;
  // in an order that depends only on the points.
  template <class F>
  void for_each_near(const Vec2& p, double r, F&& f) const {
    visit(p, r, static_cast<std::size_t>(-1), f);
  }
  // The same around point i of the grid, without i itself.
  template <class F>
  void for_each_neighbour(std::size_t i, double r, F&& f) const {
    visit(points_[i], r, i, f);
  }

  // Calls f(j, offset) for every point j != skip of the cells `ring` cells away from the
  // cell of p (Chebyshev distance; ring 0: p's own cell) with |offset| < r. A point of a
  // ring further out than `ring` is at least ring * cell() from p.
  template <class F>
  void for_each_in_ring(const Vec2& p, int ring, double r, std::size_t skip, F&& f) const {
    if (!p.allFinite() || order_.empty() || !(r > 0.0)) return;
    const int cx = cell_x(p.x()), cy = cell_y(p.y());
    const double r2 = r * r;
    auto visit_cell = [&](int x, int y) {
      if (x < 0 || x >= nx_ || y < 0 || y >= ny_) return;
      const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
      for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
        const Vec2 d = sorted_[k] - p;
        if (d.squaredNorm() < r2 && order_[k] != skip) f(static_cast<std::size_t>(order_[k]), d);
      }
    };
    if (ring == 0) return visit_cell(cx, cy);
    for (int x = cx - ring; x <= cx + ring; ++x) {  // bottom and top rows
      visit_cell(x, cy - ring);
      visit_cell(x, cy + ring);
    }
    for (int y = cy - ring + 1; y <= cy + ring - 1; ++y) {  // left and right columns
      visit_cell(cx - ring, y);
      visit_cell(cx + ring, y);
    }
  }

  double cell() const { return cell_; }

  // The indices of the finite points, cell by cell: visiting points in this order keeps
  // the neighbourhoods of consecutive queries in the cache.
  const std::vector<std::uint32_t>& cell_order() const { return order_; }

 private:
  template <class F>
  void visit(const Vec2& p, double r, std::size_t skip, F& f) const {
    if (!p.allFinite() || order_.empty() || !(r > 0.0)) return;
    const int cx = cell_x(p.x()), cy = cell_y(p.y());
    const int rings = static_cast<int>(std::min(std::ceil(r / cell_), 1e6));
    const double r2 = r * r;
    for (int y = std::max(cy - rings, 0); y <= std::min(cy + rings, ny_ - 1); ++y)
      for (int x = std::max(cx - rings, 0); x <= std::min(cx + rings, nx_ - 1); ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
        for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
          const Vec2 d = sorted_[k] - p;
          if (d.squaredNorm() < r2 && order_[k] != skip) f(static_cast<std::size_t>(order_[k]), d);
        }
      }
  }
  int cell_x(double x) const;
  int cell_y(double y) const;

  const std::vector<Vec2>& points_;
  Vec2 origin_ = Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_;  // points of cell c: order_[start_[c] .. start_[c + 1])
  std::vector<std::uint32_t> order_;
  std::vector<Vec2> sorted_;  // sorted_[k] = points_[order_[k]]
};

}  // namespace bsmpm::render

#include "paint/neighbour_grid.hpp"

#include <algorithm>
#include <cmath>

namespace bsmpm::render {

NeighbourGrid::NeighbourGrid(const std::vector<Vec2>& points, double cell) : points_(points) {
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  std::size_t finite = 0;
  for (const Vec2& p : points)
    if (p.allFinite()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
      ++finite;
    }
  if (finite == 0) {
    start_.assign(2, 0);
    return;
  }
  origin_ = lo;
  // Wider cells when a few stray points spread the cloud so far that the grid would have
  // many more cells than points.
  const Vec2 extent = hi - lo;
  cell_ = std::max(cell, 1e-12);
  const double max_cells = 4.0 * static_cast<double>(finite) + 1024.0;
  while ((extent.x() / cell_ + 1.0) * (extent.y() / cell_ + 1.0) > max_cells) cell_ *= 2.0;
  nx_ = static_cast<int>(extent.x() / cell_) + 1;
  ny_ = static_cast<int>(extent.y() / cell_) + 1;

  // Counting sort of the point indices by cell.
  const std::size_t cells = static_cast<std::size_t>(nx_) * ny_;
  start_.assign(cells + 1, 0);
  std::vector<std::uint32_t> cell_of(points.size(), UINT32_MAX);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].allFinite()) {
      cell_of[i] = static_cast<std::uint32_t>(static_cast<std::size_t>(cell_y(points[i].y())) * nx_ + cell_x(points[i].x()));
      ++start_[cell_of[i] + 1];
    }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  order_.resize(finite);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (cell_of[i] != UINT32_MAX) order_[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  sorted_.resize(finite);
  for (std::size_t k = 0; k < finite; ++k) sorted_[k] = points[order_[k]];
}

int NeighbourGrid::cell_x(double x) const {
  return std::clamp(static_cast<int>((x - origin_.x()) / cell_), 0, nx_ - 1);
}

int NeighbourGrid::cell_y(double y) const {
  return std::clamp(static_cast<int>((y - origin_.y()) / cell_), 0, ny_ - 1);
}

}  // namespace bsmpm::render

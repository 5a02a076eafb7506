#include "paint/splat_shapes.hpp"

#include <algorithm>
#include <cmath>

#include "paint/neighbour_grid.hpp"
#include "paint/splat_builder.hpp"

namespace bsmpm::render {

namespace {

// Yu & Turk weigh neighbours within twice the spacing for the covariance: close enough to
// follow a curved surface, wide enough to see which way it runs.
constexpr double kCovarianceRadius = 2.0;
// The first, cheap look around a particle, in spacings: enough to find a neighbour in every
// 45-degree sector around a particle inside intact material.
constexpr double kNearRadius = 2.0;
// Then the look widens by rings of grid cells this many (capped) spacings wide.
constexpr double kRingWidth = 1.0;

double finite_or_zero(double x) { return std::isfinite(x) && x > 0.0 ? x : 0.0; }

// Neighbours of one particle: offsets and their lengths.
struct Around {
  std::vector<Vec2> offset;
  std::vector<double> distance;

  void clear() {
    offset.clear();
    distance.clear();
  }
  void add(const Vec2& d) {
    offset.push_back(d);
    distance.push_back(d.norm());
  }
};

}  // namespace

void compute_splat_shapes(const std::vector<Vec2>& position, const std::vector<double>& side, double margin_scale,
                          const SplatObstacles& obstacles, std::vector<SplatShape>& out) {
  const std::size_t n = position.size();
  out.assign(n, SplatShape{});
  if (n == 0) return;
  // A few particles of outsized volume would make every query visit a large area: search
  // radii are capped at those of twice the median spacing.
  std::vector<double> spacing(n);
  for (std::size_t i = 0; i < n; ++i) spacing[i] = finite_or_zero(side[i]);
  std::vector<double> sorted = spacing;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double median = sorted[n / 2], largest = *std::max_element(spacing.begin(), spacing.end());
  const double cap = std::min(largest, 2.0 * median);
  static const std::vector<Vec2> kNone;
  const std::vector<Vec2>& obstacle = obstacles.particles ? *obstacles.particles : kNone;
  const NeighbourGrid grid(position, kRingWidth * cap), obstacle_grid(obstacle, kNearRadius * cap);

  // Widening looks, each settling what it can (SplatBuilder::Result::settled: nothing
  // farther away could change the splat, so the result is the widest look's). Most
  // particles lie inside intact material, where the neighbours within kNearRadius settle
  // the splat; in the world's axes, which spares the covariance: inside the material the
  // supports cut nothing. The others - at a free surface, a gap, a wall or an obstacle -
  // are shaped again in the axes of their neighbourhood, with the walls and obstacles, from
  // rings of grid cells ever further out, up to kNeighbourRadius: a particle at the edge
  // of a gap stops once it sees across.
  const double cell = grid.cell();
  const std::vector<std::uint32_t>& order = grid.cell_order();
#pragma omp parallel if (order.size() > 4096)
  {
    Around around;
#pragma omp for schedule(dynamic, 1024)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(order.size()); ++k) {
      const std::size_t i = order[static_cast<std::size_t>(k)];
      const Vec2& x = position[i];
      const double s = spacing[i], margin = 0.5 * margin_scale * s, scale = std::min(s, cap);
      const double near_radius = kNearRadius * scale, radius = kNeighbourRadius * scale;
      // Everything within `radius` in the rings that hold the near look.
      const int near_rings = static_cast<int>(std::ceil(near_radius / cell));
      const int rings = static_cast<int>(std::ceil(radius / cell));
      around.clear();
      for (int ring = 0; ring <= near_rings; ++ring)
        grid.for_each_in_ring(x, ring, radius, i, [&](std::size_t, const Vec2& d) { around.add(d); });
      SplatBuilder near(Vec2(1.0, 0.0), s, margin);
      for (std::size_t j = 0; j < around.offset.size(); ++j)
        if (around.distance[j] < near_radius) near.add_neighbour(around.offset[j], around.distance[j]);
      SplatBuilder::Result result = near.finish(near_radius);
      if (result.settled) {
        out[i] = result.shape;
        continue;
      }

      // The covariance needs only the neighbours within kCovarianceRadius <= kNearRadius.
      SplatBuilder wide(principal_axis(around.offset, around.distance, kCovarianceRadius * s), s, margin);
      if (const WorldRect* walls = obstacles.walls) {  // before the neighbours: they are mirrored
        wide.add_wall(Vec2(-1.0, 0.0), x.x() - walls->min.x(), radius);
        wide.add_wall(Vec2(1.0, 0.0), walls->max.x() - x.x(), radius);
        wide.add_wall(Vec2(0.0, -1.0), x.y() - walls->min.y(), radius);
        wide.add_wall(Vec2(0.0, 1.0), walls->max.y() - x.y(), radius);
      }
      obstacle_grid.for_each_near(x, radius, [&](std::size_t, const Vec2& d) { wide.add_obstacle(d); });
      for (std::size_t j = 0; j < around.offset.size(); ++j) wide.add_neighbour(around.offset[j], around.distance[j]);
      // After rings 0 .. R, every point not seen yet is at least R cells away.
      result = wide.finish(std::min(near_rings * cell, radius));
      for (int ring = near_rings + 1; ring <= rings && !result.settled; ++ring) {
        grid.for_each_in_ring(x, ring, radius, i, [&](std::size_t, const Vec2& d) { wide.add_neighbour(d, d.norm()); });
        result = wide.finish(std::min(ring * cell, radius));
      }
      out[i] = result.shape;
    }
  }
}

}  // namespace bsmpm::render

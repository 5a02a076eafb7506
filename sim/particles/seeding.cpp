#include "particles/seeding.hpp"

#include <algorithm>
#include <cmath>

namespace bsmpm {

SeededPoints seed_particles(const Shape& shape, const Vec2& lattice_origin,
                            const Vec2& target_spacing) {
  SeededPoints out;
  if (const auto* r = std::get_if<Rectangle>(&shape)) {
    const Vec2 size = r->max - r->min;
    const int nx = std::max(1, static_cast<int>(std::lround(size.x() / target_spacing.x())));
    const int ny = std::max(1, static_cast<int>(std::lround(size.y() / target_spacing.y())));
    out.spacing = {size.x() / nx, size.y() / ny};
    const double volume = out.spacing.prod();
    out.positions.reserve(static_cast<std::size_t>(nx) * ny);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        out.positions.push_back(r->min + Vec2((i + 0.5) * out.spacing.x(), (j + 0.5) * out.spacing.y()));
        out.volumes.push_back(volume);
      }
    return out;
  }
  out.spacing = target_spacing;
  const Rectangle box = bounding_box(shape);
  const Vec2 d = target_spacing;
  const int i0 = static_cast<int>(std::floor((box.min.x() - lattice_origin.x()) / d.x()));
  const int i1 = static_cast<int>(std::ceil((box.max.x() - lattice_origin.x()) / d.x()));
  const int j0 = static_cast<int>(std::floor((box.min.y() - lattice_origin.y()) / d.y()));
  const int j1 = static_cast<int>(std::ceil((box.max.y() - lattice_origin.y()) / d.y()));
  for (int i = i0; i <= i1; ++i)
    for (int j = j0; j <= j1; ++j) {
      const Vec2 q = lattice_origin + Vec2((i + 0.5) * d.x(), (j + 0.5) * d.y());
      if (contains(shape, q)) {
        out.positions.push_back(q);
        out.volumes.push_back(d.prod());
      }
    }
  return out;
}

}  // namespace bsmpm

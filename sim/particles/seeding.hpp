// Filling a shape with material points.
#pragma once

#include <vector>

#include "core/types.hpp"
#include "particles/shapes.hpp"

namespace bsmpm {

struct SeededPoints {
  std::vector<Vec2> positions;
  std::vector<double> volumes;
  Vec2 spacing = Vec2::Zero();
};

// Rectangles are filled exactly: round(width / target spacing) columns of equal width, so
// the particle volumes add up to the rectangle's area. Other shapes take the points of the
// lattice (origin + (k + 1/2) spacing) that fall inside them, each of volume dx * dy.
SeededPoints seed_particles(const Shape& shape, const Vec2& lattice_origin,
                            const Vec2& target_spacing);

}  // namespace bsmpm

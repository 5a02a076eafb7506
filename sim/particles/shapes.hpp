// Plane shapes that bodies are cut from.
#pragma once

#include <variant>
#include <vector>

#include "core/types.hpp"

namespace bsmpm {

struct Rectangle {
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();
};

struct Disk {
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
};

// Simple polygon, vertices in either orientation.
struct Polygon {
  std::vector<Vec2> vertices;
};

using Shape = std::variant<Rectangle, Disk, Polygon>;

bool contains(const Shape& shape, const Vec2& point);
double area(const Shape& shape);
Rectangle bounding_box(const Shape& shape);

// Round-off allowance for geometry compared with the domain's edges.
double domain_tolerance(const Rectangle& domain);
// Whether `r` reaches outside `domain` by more than that allowance.
bool extends_outside(const Rectangle& r, const Rectangle& domain);

}  // namespace bsmpm

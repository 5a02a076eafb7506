#include "particles/shapes.hpp"

#include <cmath>

namespace bsmpm {

namespace {
struct Contains {
  const Vec2& q;
  bool operator()(const Rectangle& r) const {
    return q.x() >= r.min.x() && q.x() <= r.max.x() && q.y() >= r.min.y() && q.y() <= r.max.y();
  }
  bool operator()(const Disk& d) const { return (q - d.center).squaredNorm() <= d.radius * d.radius; }
  bool operator()(const Polygon& poly) const {
    // Even-odd rule with a horizontal ray.
    bool inside = false;
    const auto& v = poly.vertices;
    for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
      if ((v[i].y() > q.y()) != (v[j].y() > q.y())) {
        const double x_cross =
            v[j].x() + (q.y() - v[j].y()) * (v[i].x() - v[j].x()) / (v[i].y() - v[j].y());
        if (q.x() < x_cross) inside = !inside;
      }
    }
    return inside;
  }
};

struct Area {
  double operator()(const Rectangle& r) const { return (r.max - r.min).prod(); }
  double operator()(const Disk& d) const { return kPi * d.radius * d.radius; }
  double operator()(const Polygon& poly) const {
    double a = 0.0;  // shoelace formula
    const auto& v = poly.vertices;
    for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
      a += v[j].x() * v[i].y() - v[i].x() * v[j].y();
    return 0.5 * std::abs(a);
  }
};

struct Bounds {
  Rectangle operator()(const Rectangle& r) const { return r; }
  Rectangle operator()(const Disk& d) const {
    return {d.center - Vec2::Constant(d.radius), d.center + Vec2::Constant(d.radius)};
  }
  Rectangle operator()(const Polygon& poly) const {
    Rectangle b{poly.vertices.front(), poly.vertices.front()};
    for (const auto& p : poly.vertices) {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
    }
    return b;
  }
};
}  // namespace

bool contains(const Shape& shape, const Vec2& point) { return std::visit(Contains{point}, shape); }
double area(const Shape& shape) { return std::visit(Area{}, shape); }
Rectangle bounding_box(const Shape& shape) { return std::visit(Bounds{}, shape); }

double domain_tolerance(const Rectangle& domain) { return 1e-9 * (domain.max - domain.min).norm(); }

bool extends_outside(const Rectangle& r, const Rectangle& domain) {
  const double tol = domain_tolerance(domain);
  return (r.min.array() < domain.min.array() - tol).any() || (r.max.array() > domain.max.array() + tol).any();
}

}  // namespace bsmpm

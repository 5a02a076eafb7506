#include "probes/front_probe.hpp"

#include <cmath>
#include <limits>

#include "core/format.hpp"

namespace bsmpm {

std::string FrontProbe::describe() const {
  return format("%s: front of %s along (%.3g, %.3g)", name().c_str(), body_name_.c_str(), direction_.x(),
                direction_.y());
}

void FrontProbe::sample(const ProbeContext& ctx, double* row) {
  const Body& body = ctx.bodies[body_];
  double front = -std::numeric_limits<double>::infinity();
  for (std::size_t p = body.begin; p < body.end; ++p) front = std::max(front, ctx.particles.x[p].dot(direction_));
  const double half = 0.5 * (std::abs(direction_.x()) * body.spacing.x() + std::abs(direction_.y()) * body.spacing.y());
  row[0] = ctx.time;
  row[1] = ctx.time * scales_.time_factor();
  row[2] = front + half;
}

}  // namespace bsmpm

#include "probes/material_point.hpp"

#include <limits>

#include "core/format.hpp"

namespace bsmpm {

MaterialPoint::MaterialPoint(const Particles& particles, const Body& body, const Vec2& X) : X_(X) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t p = body.begin; p < body.end; ++p) {
    const double d2 = (particles.x0[p] - X).squaredNorm();
    if (d2 < best) {
      best = d2;
      id_ = particles.id[p];
      Xp_ = particles.x0[p];
    }
  }
}

Vec2 MaterialPoint::position(const ProbeContext& ctx) const {
  const std::size_t p = ctx.index_of_id[id_];
  return ctx.particles.x[p] + ctx.particles.F[p] * (X_ - Xp_);
}

Vec2 MaterialPoint::normal(const ProbeContext& ctx, const Vec2& N) const {
  const std::size_t p = ctx.index_of_id[id_];
  return (ctx.particles.F[p].inverse().transpose() * N).normalized();
}

std::string MaterialPointProbe::describe() const {
  return format("%s: material point of %s at (%.4g, %.4g) m", name().c_str(), body_name_.c_str(),
                point_.reference().x(), point_.reference().y());
}

void MaterialPointProbe::sample(const ProbeContext& ctx, double* row) {
  const Vec2 x = point_.position(ctx);
  row[0] = ctx.time;
  row[1] = x.x() - point_.reference().x();
  row[2] = x.y() - point_.reference().y();
  row[3] = x.x();
  row[4] = x.y();
}

}  // namespace bsmpm

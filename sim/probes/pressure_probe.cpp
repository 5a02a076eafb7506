#include "probes/pressure_probe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/format.hpp"

namespace bsmpm {

PressureProbe::PressureProbe(std::string name, double interval, Vec2 centre, Vec2 normal,
                             PressureSensor sensor, std::vector<int> fluid_bodies,
                             ReferenceScales scales, std::string where)
    : Probe(std::move(name), interval), moving_(false), centre_(centre), normal_(normal.normalized()),
      sensor_(sensor), fluid_bodies_(std::move(fluid_bodies)), scales_(scales), where_(std::move(where)) {}

PressureProbe::PressureProbe(std::string name, double interval, MaterialPoint anchor, Vec2 normal,
                             PressureSensor sensor, std::vector<int> fluid_bodies,
                             ReferenceScales scales, std::string where)
    : Probe(std::move(name), interval), moving_(true), centre_(anchor.reference()), anchor_(anchor),
      normal_(normal.normalized()), sensor_(sensor), fluid_bodies_(std::move(fluid_bodies)),
      scales_(scales), where_(std::move(where)) {}

std::string PressureProbe::describe() const {
  return format("%s: pressure on %s at (%.4g, %.4g) m, footprint %g mm x %g mm", name().c_str(), where_.c_str(),
                centre_.x(), centre_.y(), sensor_.size * 1e3, sensor_.depth * 1e3);
}

double PressureProbe::footprint_pressure(const ProbeContext& ctx, const std::vector<int>& fluid_bodies,
                                         const Vec2& centre, const Vec2& normal,
                                         const PressureSensor& sensor) {
  const Vec2 tangent(-normal.y(), normal.x());
  const double half = 0.5 * sensor.size;
  const Particles& ps = ctx.particles;
  // Blocks of a fixed size, summed in order: the same bits for any thread count.
  constexpr std::size_t kBlock = 1024;
  double weighted = 0.0, volume = 0.0;
  for (int b : fluid_bodies) {
    const Body& body = ctx.bodies[b];
    const long blocks = static_cast<long>((body.size() + kBlock - 1) / kBlock);
    static thread_local std::vector<std::array<double, 2>> partial;  // kept: no allocation after the first
    partial.resize(blocks);
    std::array<double, 2>* const out = partial.data();  // the caller's: thread_local is per thread
#pragma omp parallel for schedule(static) if (blocks > 1)
    for (long k = 0; k < blocks; ++k) {
      const std::size_t first = body.begin + k * kBlock, last = std::min(body.end, first + kBlock);
      double w = 0.0, v = 0.0;
      for (std::size_t p = first; p < last; ++p) {
        const Vec2 d = ps.x[p] - centre;
        const double along = d.dot(tangent), into = d.dot(normal);
        if (std::abs(along) <= half && into >= 0.0 && into <= sensor.depth) {
          const double V = ps.volume(p);
          w += V * ps.pressure[p];
          v += V;
        }
      }
      out[k] = {w, v};
    }
    for (long k = 0; k < blocks; ++k) {
      weighted += partial[k][0];
      volume += partial[k][1];
    }
  }
  return volume > 0.0 ? weighted / volume : 0.0;
}

void PressureProbe::sample(const ProbeContext& ctx, double* row) {
  Vec2 centre = centre_, normal = normal_;
  if (moving_) {
    centre = anchor_.position(ctx);
    normal = anchor_.normal(ctx, normal_);
  }
  const double P = footprint_pressure(ctx, fluid_bodies_, centre, normal, sensor_);
  row[0] = ctx.time;
  row[1] = ctx.time * scales_.time_factor();
  row[2] = P;
  row[3] = P / scales_.pressure_scale();
}

}  // namespace bsmpm

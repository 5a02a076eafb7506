#include "probes/wall_reaction_probe.hpp"

#include "core/boundaries.hpp"
#include "core/format.hpp"
#include "probes/pressure_probe.hpp"

namespace bsmpm {

WallReactionProbe::WallReactionProbe(std::string name, double interval, int wall, double centre,
                                     double face_length, std::vector<double> share, ReferenceScales scales)
    : Probe(std::move(name), interval), wall_(wall), centre_(centre), face_length_(face_length),
      share_(std::move(share)), scales_(scales) {}

std::vector<std::string> WallReactionProbe::columns() const { return PressureProbe::column_names(); }
std::vector<std::string> WallReactionProbe::units() const { return PressureProbe::column_units(); }

std::string WallReactionProbe::describe() const {
  return format("%s: reaction of the %s wall at %.4g m, face %g mm", name().c_str(), wall_side_name(wall_), centre_,
                face_length_ * 1e3);
}

void WallReactionProbe::sample(const ProbeContext& ctx, double* row) {
  // docs/method.md §8, eq. S2: P = -(sum_k s_k I_k . n) / (dt L), n the wall's outward
  // normal, I_k the impulse on the water at control point k, s_k its share of the face.
  double P = 0.0;
  if (ctx.wall_impulse && ctx.dt > 0.0) {
    const std::vector<Vec2>& impulse = (*ctx.wall_impulse)[wall_];
    if (impulse.size() == share_.size()) {
      const int axis = wall_ == kLeft || wall_ == kRight ? 0 : 1;
      const double outward = wall_ == kLeft || wall_ == kBottom ? -1.0 : 1.0;
      double push = 0.0;
      for (std::size_t k = 0; k < share_.size(); ++k) push += share_[k] * impulse[k][axis];
      P = -outward * push / (ctx.dt * face_length_);
    }
  }
  row[0] = ctx.time;
  row[1] = ctx.time * scales_.time_factor();
  row[2] = P;
  row[3] = P / scales_.pressure_scale();
}

}  // namespace bsmpm

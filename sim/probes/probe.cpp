#include "probes/probe.hpp"

#include <cmath>

namespace bsmpm {

double ReferenceScales::time_factor() const { return std::sqrt(gravity / length); }
double ReferenceScales::pressure_scale() const { return density * gravity * length; }

void Probe::maybe_sample(const ProbeContext& ctx) {
  // A billionth of the interval absorbs the round-off of t += dt.
  if (interval_ > 0.0 && ctx.time < next_time_ - 1e-9 * interval_) return;
  const std::size_t n = columns_count();
  data_.resize(data_.size() + n);
  sample(ctx, data_.data() + data_.size() - n);
  if (interval_ > 0.0) {
    const bool first = next_time_ < -1.0e299;
    next_time_ = first ? ctx.time + interval_ : next_time_ + interval_;
    if (next_time_ <= ctx.time) next_time_ = ctx.time + interval_;  // dt > interval
  }
}

}  // namespace bsmpm

#include "figure/color_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace bsmpm::render {

namespace {

// The q-quantile (0..1) of `values` by nearest rank; reorders `values`.
double quantile(std::vector<double>& values, double q) {
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(std::floor(q * (values.size() - 1) + 0.5)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

ValueRange scan_range(const RunReader& run, Field field, ParticleKind kind) {
  const auto& body_of = run.particle_bodies();
  const auto& bodies = run.bodies();
  auto wanted = [&](std::size_t k) {
    const RunBodyInfo& b = bodies[body_of[k]];
    return kind == ParticleKind::kWater ? b.is_fluid() : b.is_solid();
  };
  const bool spread = field != Field::kDisplacement;
  const double q_low = spread ? 0.005 : 0.0, q_high = spread ? 0.995 : 1.0;

  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  std::vector<double> values;
  for (const RunFrameInfo& f : run.frames()) {
    const std::vector<double> all = field_values(run, f.index, field);
    values.clear();
    for (std::size_t k = 0; k < all.size(); ++k)
      if (wanted(k) && std::isfinite(all[k])) values.push_back(all[k]);
    if (values.empty()) continue;
    lo = std::min(lo, quantile(values, q_low));
    hi = std::max(hi, quantile(values, q_high));
  }
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {0.0, 1.0};
  lo = std::min(lo, 0.0);
  if (!(hi > lo)) hi = lo + 1.0 / field_info(field).display_scale;
  return {lo, hi};
}

}  // namespace bsmpm::render

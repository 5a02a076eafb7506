// Body force m g on the control points (eq. 8, first term): since sum_p m_p b S_Ip =
// m_I b for a uniform b, gravity costs one pass over the active nodes, not over particles.
// A bed slope theta rotates gravity in the tank frame (paper Fig. 9; the reading in
// docs/method.md §2, step 3).
#pragma once

#include <cmath>

#include "core/format.hpp"
#include "step/effect.hpp"

namespace bsmpm {

inline Vec2 gravity_vector(double g, double slope_deg) {
  const double theta = slope_deg * kPi / 180.0;
  return {g * std::sin(theta), -g * std::cos(theta)};
}

template <int P>
class Gravity final : public Effect<P> {
 public:
  Gravity(double g, double slope_deg) : g_(g), slope_deg_(slope_deg), b_(gravity_vector(g, slope_deg)) {}

  unsigned hooks() const override { return kHookGridForces; }
  std::string describe() const override {
    return format("gravity: g = %g m/s2, bed slope %g deg (g = [%.4g, %.4g])", g_, slope_deg_, b_.x(), b_.y());
  }
  void grid_forces(StepState<P>& st) override {
    const int ny = st.grid.ny();
    for (auto& layer : st.layers)
      for_each_node(layer.active, ny, [&](int n, int, int) { layer.force[n] += layer.mass[n] * b_; });
  }

 private:
  double g_, slope_deg_;
  Vec2 b_;
};

}  // namespace bsmpm

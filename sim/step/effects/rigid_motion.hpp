// Rigid obstacles of prescribed motion: every control point of a rigid body's own field
// carries the body's velocity, so contact sees it as the limit m -> infinity (docs/method.md §5).
#pragma once

#include <string>
#include <vector>

#include "core/format.hpp"
#include "step/effect.hpp"

namespace bsmpm {

template <int P>
class RigidMotion final : public Effect<P> {
 public:
  struct Rigid {
    std::string body;
    int layer;
    Vec2 velocity;
  };
  explicit RigidMotion(std::vector<Rigid> bodies) : bodies_(std::move(bodies)) {}

  unsigned hooks() const override { return kHookConstrainVelocity; }
  std::string describe() const override {
    std::string s = "rigid motion:";
    for (const auto& r : bodies_) s += format(" %s at (%g, %g) m/s", r.body.c_str(), r.velocity.x(), r.velocity.y());
    return s;
  }
  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override {
    const int ny = st.grid.ny();
    for (const auto& r : bodies_) {
      GridLayer& layer = st.layers[r.layer];
      auto& v = phase_velocity(layer, phase);
      for_each_node(layer.active, ny, [&](int n, int, int) {
        if (layer.mass[n] > st.mass_cutoff) v[n] = r.velocity;
      });
    }
  }

 private:
  std::vector<Rigid> bodies_;
};

}  // namespace bsmpm

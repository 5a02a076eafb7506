// Rigid obstacles of prescribed motion: every control point of a rigid body's own field
// carries the body's velocity, so contact sees it as the limit m -> infinity (docs/method.md §5).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "step/effects/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// No table of its own: every body of a rigid material moves at that material's velocity
// ([materials.NAME] type = "rigid", velocity = [vx, vy]).
struct RigidMotionParameters {
  std::vector<int> bodies;  // the rigid ones

  static std::optional<RigidMotionParameters> read(SceneTables& scene) {
    RigidMotionParameters p;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      if (is_rigid(scene.bodies[b].material)) p.bodies.push_back(static_cast<int>(b));
    if (p.bodies.empty()) return std::nullopt;
    return p;
  }
};

template <int P>
class RigidMotion final : public EffectBase<RigidMotion<P>, P> {
 public:
  using Parameters = RigidMotionParameters;
  // Before contact, which then sees the rigid bodies' velocities.
  static constexpr EffectPhase kPhase = EffectPhase::kPrescribedMotion;
  struct Rigid {
    std::string body;
    int layer;
    Vec2 velocity;
  };
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>& st) {
    std::vector<Rigid> rigid;
    for (int b : p.bodies) {
      const Body& body = st.bodies[b];
      rigid.push_back({body.name, body.layer, std::get<RigidBody>(body.material).velocity});
    }
    return std::make_unique<RigidMotion>(std::move(rigid));
  }

  explicit RigidMotion(std::vector<Rigid> bodies) : bodies_(std::move(bodies)) {}

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

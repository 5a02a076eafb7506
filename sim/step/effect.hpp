// Optional effects composed per scene (after Karamelo's fixes and SPlisHSPlasH's
// per-effect classes): each effect says which hooks of the step it uses, the step keeps
// one list per hook, and an effect that a scene does not ask for is simply absent.
#pragma once

#include <string>
#include <vector>

#include "step/step_state.hpp"

namespace bsmpm {

enum EffectHook : unsigned {
  kHookGridForces = 1u << 0,        // add nodal forces after P2G (eq. 8)
  kHookConstrainVelocity = 1u << 1, // essential conditions on nodal velocities
};

// The constraints run twice per step: on v_I^{k+1} (docs/method.md §2, step 5) and on the
// remapped velocities of eq. 13 (step 7).
enum class VelocityPhase { kUpdate, kRemap };

inline std::vector<Vec2>& phase_velocity(GridLayer& layer, VelocityPhase phase) {
  return phase == VelocityPhase::kUpdate ? layer.velocity : layer.remap_velocity;
}

template <int P>
class Effect {
 public:
  virtual ~Effect() = default;
  virtual unsigned hooks() const = 0;
  // One line for the start-of-run summary: "name: details".
  virtual std::string describe() const = 0;
  virtual void grid_forces(StepState<P>&) {}
  virtual void constrain_velocity(StepState<P>&, VelocityPhase) {}
};

}  // namespace bsmpm

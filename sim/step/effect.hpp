// Optional effects composed per scene (after Karamelo's fixes and SPlisHSPlasH's
// per-effect classes): the step keeps one list per hook, and an effect that a scene does not
// ask for is simply absent. An effect derives from EffectBase, which works out the hooks it
// uses from the methods it overrides and its place in them from its declared phase; it reads
// its own parameters and builds itself (scene/effect_registry.cpp lists them).
#pragma once

#include <string>
#include <type_traits>
#include <vector>

#include "step/step_state.hpp"

namespace bsmpm {

enum EffectHook : unsigned {
  kHookGridForces = 1u << 0,        // add nodal forces after P2G (eq. 8)
  kHookConstrainVelocity = 1u << 1, // essential conditions on nodal velocities
  kHookProjectVelocity = 1u << 2,   // the constrained v_I^{k+1} projected (incompressible fluid, method.md §12)
};

// Where an effect runs within its hook: the step sorts its effects by phase (stably, so
// effects of one phase keep their registration order).
enum class EffectPhase {
  kBodyForce,         // forces on the nodes (eq. 8)
  kForceDamping,      // acts on the summed nodal force: after every force is in
  kPrescribedMotion,  // velocities of bodies whose motion is given (rigid bodies)
  kContact,           // exchanges momentum between fields: sees the prescribed motion
  kWalls,             // the tank's walls hold exactly, whatever contact did
  kClamps,            // clamped control points are at rest, last of all
  kProjection,        // after every constraint: the pressure that keeps the fluid's volume
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
  virtual unsigned hooks() const = 0;      // derived by EffectBase, never written by hand
  virtual EffectPhase phase() const = 0;   // E::kPhase, through EffectBase
  // One line for the start-of-run summary: "name: details".
  virtual std::string describe() const = 0;
  virtual void grid_forces(StepState<P>&) {}
  virtual void constrain_velocity(StepState<P>&, VelocityPhase) {}
  // Once per step, on the constrained v_I^{k+1} of the update phase, before the particles
  // read it (docs/method.md §2, between steps 5 and 6).
  virtual void project_velocity(StepState<P>&) {}
  // State an effect carries from one step to the next beyond the particles (e.g. the pressure
  // the next solve starts from): appended to `out`; read back from `in` at `at`, returning
  // where the next effect's starts. A checkpoint holds it, so a resumed run gives the same bits.
  virtual void save_state(std::vector<double>& /*out*/) const {}
  virtual std::size_t load_state(const std::vector<double>& /*in*/, std::size_t at) { return at; }
};

// The base of every effect E (CRTP): hooks() holds exactly the methods E overrides, so the
// step never skips one, and phase() is E::kPhase.
template <class E, int P>
class EffectBase : public Effect<P> {
 public:
  static constexpr unsigned derived_hooks() {
    unsigned mask = 0;
    if constexpr (!std::is_same_v<decltype(&E::grid_forces), decltype(&Effect<P>::grid_forces)>)
      mask |= kHookGridForces;
    if constexpr (!std::is_same_v<decltype(&E::constrain_velocity), decltype(&Effect<P>::constrain_velocity)>)
      mask |= kHookConstrainVelocity;
    if constexpr (!std::is_same_v<decltype(&E::project_velocity), decltype(&Effect<P>::project_velocity)>)
      mask |= kHookProjectVelocity;
    return mask;
  }
  unsigned hooks() const final {
    static_assert(derived_hooks() != 0, "an effect overrides grid_forces, constrain_velocity or project_velocity");
    return derived_hooks();
  }
  EffectPhase phase() const final { return E::kPhase; }
};

}  // namespace bsmpm

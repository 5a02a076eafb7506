// The effects a scene can ask for, one per line in RegisteredEffects. Each one reads its own
// keys from the scene (its Parameters::read, after pbrt-v4's parameter dictionaries) and
// builds itself from what it read (its create); SceneDescription keeps the parameters in
// between as plain typed data, one optional per effect (EffectParameters).
#pragma once

#include <memory>
#include <optional>
#include <tuple>
#include <type_traits>
#include <vector>

#include "contact/li_lian_2024_contact.hpp"
#include "step/effect.hpp"
#include "step/effects/clamped_nodes.hpp"
#include "step/effects/gravity.hpp"
#include "step/effects/local_damping.hpp"
#include "step/effects/rigid_motion.hpp"
#include "step/effects/scene_tables.hpp"
#include "step/effects/tank_walls.hpp"
#include "step/incompressible/pressure_projection.hpp"

namespace bsmpm {

// An effect E<P> names its Parameters (one type for every P), reads them with
// Parameters::read (std::nullopt: the scene does not ask for E) and builds itself with
// E<P>::create (nullptr: nothing to do after all).
template <template <int> class... Effects>
struct EffectList {
  // The parameters of every effect, each absent when the scene does not ask for it.
  using Parameters = std::tuple<std::optional<typename Effects<1>::Parameters>...>;

  static Parameters read(SceneTables& scene) {
    // Braced initialisation reads the effects in the order they are listed.
    return Parameters{Effects<1>::Parameters::read(scene)...};
  }

  // In the order they are listed; the step then runs them in the order of their phases.
  template <int P>
  static std::vector<std::unique_ptr<Effect<P>>> create(const Parameters& all, const StepState<P>& st) {
    std::vector<std::unique_ptr<Effect<P>>> out;
    auto create_one = [&](auto tag, const auto& parameters) {
      using E = typename decltype(tag)::type;
      if (parameters)
        if (auto effect = E::create(*parameters, st)) out.push_back(std::move(effect));
    };
    std::apply([&](const auto&... parameters) { (create_one(std::type_identity<Effects<P>>{}, parameters), ...); },
               all);
    return out;
  }
};

// Every effect a scene can ask for, one per line. Scenes are read in this order; the step
// runs the effects in the order of their phases (EffectPhase).
using RegisteredEffects = EffectList<
    Gravity,
    LocalDamping,
    RigidMotion,
    LiLian2024Contact,
    TankWalls,
    ClampedNodes,
    PressureProjection>;

// What the scene asks of each effect, by the type of its parameters:
// `scene.effects.get<GravityParameters>()` is the gravity or nullptr when the scene has none.
struct EffectParameters {
  RegisteredEffects::Parameters all;

  template <class T>
  const T* get() const {
    const std::optional<T>& p = std::get<std::optional<T>>(all);  // T must be a registered effect's
    return p ? &*p : nullptr;
  }
};

inline EffectParameters read_effects(SceneTables& scene) { return {RegisteredEffects::read(scene)}; }

// The effects built from what the scene asked for, for spline order P.
template <int P>
std::vector<std::unique_ptr<Effect<P>>> create_effects(const EffectParameters& parameters, const StepState<P>& state) {
  return RegisteredEffects::create<P>(parameters.all, state);
}

}  // namespace bsmpm

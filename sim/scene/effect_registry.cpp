#include "scene/effect_registry.hpp"

#include <type_traits>

#include "contact/li_lian_2024_contact.hpp"
#include "step/effects/clamped_nodes.hpp"
#include "step/effects/gravity.hpp"
#include "step/effects/local_damping.hpp"
#include "step/effects/rigid_motion.hpp"
#include "step/effects/tank_walls.hpp"

namespace bsmpm {

namespace {

// An effect E<P> names its Parameters (one type for every P), reads them with
// Parameters::read (std::nullopt: the scene does not ask for E) and builds itself with
// E<P>::create (nullptr: nothing to do after all).
template <template <int> class... Effects>
struct EffectList {
  template <class T, class... Ts>
  static constexpr bool distinct() {
    if constexpr (sizeof...(Ts) == 0) return true;
    else return (!std::is_same_v<T, Ts> && ...) && distinct<Ts...>();
  }
  // create() finds an effect by the type of its parameters.
  static_assert(distinct<typename Effects<1>::Parameters...>(), "two effects share a Parameters type");

  static std::vector<std::any> read(SceneTables& scene) {
    std::vector<std::any> out;
    auto read_one = [&](auto parameters) {
      if (parameters) out.emplace_back(std::move(*parameters));
    };
    (read_one(Effects<1>::Parameters::read(scene)), ...);
    return out;
  }

  template <int P>
  static std::vector<std::unique_ptr<Effect<P>>> create(const std::vector<std::any>& all, const StepState<P>& st) {
    std::vector<std::unique_ptr<Effect<P>>> out;
    for (const std::any& parameters : all) (create_one<Effects<P>>(parameters, st, out), ...);
    return out;
  }

  template <class E, int P>
  static void create_one(const std::any& parameters, const StepState<P>& st,
                         std::vector<std::unique_ptr<Effect<P>>>& out) {
    if (const auto* p = std::any_cast<typename E::Parameters>(&parameters))
      if (auto effect = E::create(*p, st)) out.push_back(std::move(effect));
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
    ClampedNodes>;

}  // namespace

std::vector<std::any> read_effects(SceneTables& scene) { return RegisteredEffects::read(scene); }

template <int P>
std::vector<std::unique_ptr<Effect<P>>> create_effects(const std::vector<std::any>& parameters,
                                                       const StepState<P>& state) {
  return RegisteredEffects::create<P>(parameters, state);
}

template std::vector<std::unique_ptr<Effect<1>>> create_effects<1>(const std::vector<std::any>&, const StepState<1>&);
template std::vector<std::unique_ptr<Effect<2>>> create_effects<2>(const std::vector<std::any>&, const StepState<2>&);
template std::vector<std::unique_ptr<Effect<3>>> create_effects<3>(const std::vector<std::any>&, const StepState<3>&);

}  // namespace bsmpm

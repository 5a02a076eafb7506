// The contract between the step and its effects: an effect's hooks are exactly the methods
// it overrides, and the step runs effects in the order of their declared phases, whatever
// order they were given in.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "contact/li_lian_2024_contact.hpp"
#include "step/bsmpm_simulation.hpp"
#include "step/effects/clamped_nodes.hpp"
#include "step/effects/gravity.hpp"
#include "step/effects/local_damping.hpp"
#include "step/effects/rigid_motion.hpp"
#include "step/effects/tank_walls.hpp"
#include "unit/one_body_state.hpp"

using namespace bsmpm;

namespace {

using Log = std::vector<std::string>;

// An effect that logs the calls of the hooks its subclass E overrides.
template <class E>
class Logging : public EffectBase<E, 2> {
 public:
  Logging(std::string name, Log& log) : name_(std::move(name)), log_(log) {}
  std::string describe() const override { return name_; }

 protected:
  void note(const char* hook) { log_.push_back(name_ + " " + hook); }
  void note(VelocityPhase phase) { note(phase == VelocityPhase::kUpdate ? "update" : "remap"); }

 private:
  std::string name_;
  Log& log_;
};

template <EffectPhase Phase>
class ForcesOnly final : public Logging<ForcesOnly<Phase>> {
 public:
  static constexpr EffectPhase kPhase = Phase;
  using Logging<ForcesOnly>::Logging;
  void grid_forces(StepState<2>&) override { this->note("forces"); }
};

template <EffectPhase Phase>
class ConstraintOnly final : public Logging<ConstraintOnly<Phase>> {
 public:
  static constexpr EffectPhase kPhase = Phase;
  using Logging<ConstraintOnly>::Logging;
  void constrain_velocity(StepState<2>&, VelocityPhase phase) override { this->note(phase); }
};

class Both final : public Logging<Both> {
 public:
  static constexpr EffectPhase kPhase = EffectPhase::kContact;
  using Logging<Both>::Logging;
  void grid_forces(StepState<2>&) override { note("forces"); }
  void constrain_velocity(StepState<2>&, VelocityPhase phase) override { note(phase); }
};

// A few fluid particles on a small grid.
StepState<2> small_state() {
  return test::one_body_state(Grid<2>(Vec2(0.0, 0.0), Vec2(0.1, 0.1), 6, 6), "water", WeaklyCompressibleFluid{},
                              Vec2(0.02, 0.02), [](Particles& ps) {
                                for (int k = 0; k < 9; ++k)
                                  ps.push_back(Vec2(0.2 + 0.02 * (k % 3), 0.2 + 0.02 * (k / 3)), 0.1, 1e-4, 0);
                              });
}

}  // namespace

TEST_CASE("An effect's hooks are the methods it overrides", "[effects]") {
  STATIC_REQUIRE(ForcesOnly<EffectPhase::kBodyForce>::derived_hooks() == kHookGridForces);
  STATIC_REQUIRE(ConstraintOnly<EffectPhase::kWalls>::derived_hooks() == kHookConstrainVelocity);
  STATIC_REQUIRE(Both::derived_hooks() == (kHookGridForces | kHookConstrainVelocity));
  // The registered effects.
  STATIC_REQUIRE(Gravity<2>::derived_hooks() == kHookGridForces);
  STATIC_REQUIRE(LocalDamping<2>::derived_hooks() == kHookGridForces);
  STATIC_REQUIRE(RigidMotion<2>::derived_hooks() == kHookConstrainVelocity);
  STATIC_REQUIRE(LiLian2024Contact<2>::derived_hooks() == kHookConstrainVelocity);
  STATIC_REQUIRE(TankWalls<2>::derived_hooks() == kHookConstrainVelocity);
  STATIC_REQUIRE(ClampedNodes<2>::derived_hooks() == kHookConstrainVelocity);
}

TEST_CASE("The step runs each effect in its hooks, in the order of the effects' phases", "[effects]") {
  Log log;
  std::vector<std::unique_ptr<Effect<2>>> effects;
  // Given in the wrong order on purpose.
  effects.push_back(std::make_unique<ConstraintOnly<EffectPhase::kClamps>>("clamps", log));
  effects.push_back(std::make_unique<ConstraintOnly<EffectPhase::kWalls>>("walls", log));
  effects.push_back(std::make_unique<Both>("both", log));
  effects.push_back(std::make_unique<ConstraintOnly<EffectPhase::kPrescribedMotion>>("rigid", log));
  effects.push_back(std::make_unique<ForcesOnly<EffectPhase::kForceDamping>>("damping", log));
  effects.push_back(std::make_unique<ForcesOnly<EffectPhase::kBodyForce>>("gravity", log));
  effects.push_back(std::make_unique<ConstraintOnly<EffectPhase::kWalls>>("walls 2", log));  // after "walls"
  BsmpmSimulation<2> sim(small_state(), SolverSettings{}, std::move(effects), {});

  const std::vector<std::string> described = sim.describe_effects();
  CHECK(std::vector<std::string>(described.end() - 7, described.end()) ==
        std::vector<std::string>{"gravity", "damping", "rigid", "both", "walls", "walls 2", "clamps"});

  sim.advance(1e-4);
  CHECK(log == Log{"gravity forces", "damping forces", "both forces",                                 //
                   "rigid update", "both update", "walls update", "walls 2 update", "clamps update",  //
                   "rigid remap", "both remap", "walls remap", "walls 2 remap", "clamps remap"});
}

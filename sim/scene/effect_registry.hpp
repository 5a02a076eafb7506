// The effects a scene can ask for (listed in effect_registry.cpp). Each one reads its own
// keys from the scene (its Parameters::read, after pbrt-v4's parameter dictionaries) and
// builds itself from what it read (its create); SceneDescription keeps the parameters as
// plain data in between.
#pragma once

#include <any>
#include <memory>
#include <vector>

#include "parameters/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// The parameters of every registered effect that the scene asks for, in registration order.
std::vector<std::any> read_effects(SceneTables& scene);

// The effects built from read_effects' parameters, for spline order P; the step runs them in
// the order of their phases.
template <int P>
std::vector<std::unique_ptr<Effect<P>>> create_effects(const std::vector<std::any>& parameters,
                                                       const StepState<P>& state);

extern template std::vector<std::unique_ptr<Effect<1>>> create_effects<1>(const std::vector<std::any>&,
                                                                         const StepState<1>&);
extern template std::vector<std::unique_ptr<Effect<2>>> create_effects<2>(const std::vector<std::any>&,
                                                                         const StepState<2>&);
extern template std::vector<std::unique_ptr<Effect<3>>> create_effects<3>(const std::vector<std::any>&,
                                                                         const StepState<3>&);

}  // namespace bsmpm

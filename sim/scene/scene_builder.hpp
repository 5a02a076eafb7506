// Validated SceneDescription -> a ready-to-run Simulation (stage three of the loading):
// seeds the particles, assigns grid layers and composes the effects the scene asks for.
#pragma once

#include <memory>

#include "scene/scene_description.hpp"
#include "step/simulation.hpp"

namespace bsmpm {

std::unique_ptr<Simulation> build_simulation(const SceneDescription& scene);

}  // namespace bsmpm

// The start-of-run summary: grid, bodies, time step, and the effects the scene composed.
#pragma once

#include <cstdio>

#include "scene/scene_description.hpp"
#include "step/simulation.hpp"

namespace bsmpm::cli {

void print_scene_summary(std::FILE* out, const SceneDescription& scene, const Simulation& sim, int threads);

}  // namespace bsmpm::cli

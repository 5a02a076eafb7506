// The start-of-run summary: grid, bodies, time step, and the effects the scene composed.
#pragma once

#include <cstdio>

#include <string>
#include <vector>

#include "scene/run_cost.hpp"
#include "scene/scene_description.hpp"
#include "step/simulation.hpp"

namespace bsmpm::cli {

void print_scene_summary(std::FILE* out, const SceneDescription& scene, const Simulation& sim, int threads);

// The predicted cost of the run (scene/run_cost.hpp) and the guards' warnings.
void print_run_cost(std::FILE* out, const RunCost& cost, const std::vector<std::string>& warnings);

}  // namespace bsmpm::cli

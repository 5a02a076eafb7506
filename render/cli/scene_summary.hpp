// The start-of-run summary: grid, bodies, time step, and the effects the scene composed.
#pragma once

#include <cstdio>

#include <string>
#include <vector>

#include "cli/wall_time_estimate.hpp"
#include "scene/run_cost.hpp"
#include "scene/scene_description.hpp"
#include "step/simulation.hpp"

namespace bsmpm::cli {

void print_scene_summary(std::FILE* out, const SceneDescription& scene, const Simulation& sim, int threads);

// The predicted cost of the run (scene/run_cost.hpp), its wall time on this machine and the
// warnings of the guards and of the calibration.
void print_run_cost(std::FILE* out, const RunCost& cost, const std::vector<std::string>& warnings,
                    const WallTimeEstimate& wall);

}  // namespace bsmpm::cli

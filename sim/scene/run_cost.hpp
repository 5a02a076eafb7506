// What a run will cost, predicted from the scene description alone, before a particle is
// seeded (so that `bsmpm check` answers at once for any scene): particles, memory, time steps,
// particle-steps and output size. `bsmpm check`, the start of `bsmpm run` and the resource
// guards (run_guards.hpp) all read this one prediction.
#pragma once

#include <string>

#include "scene/scene_description.hpp"

namespace bsmpm {

struct RunCost {
  double particles = 0.0;       // as seeding will place them (exact for rectangles)
  double rigid_particles = 0.0; // of them in rigid bodies
  int grid_fields = 1;          // velocity fields (one per body in contact, else one)
  double control_points = 0.0;  // per field
  double memory_bytes = 0.0;    // particles, grid fields and scratch of the running step
  // The time step: the fastest signal expected (the stiffest material's wave speed plus the
  // flow speed a fall from the highest fluid gives), and the step count it leads to.
  double signal_speed = 0.0;    // m/s
  std::string stiffest_body;    // whose wave speed sets it
  double wave_speed = 0.0;      // that body's wave speed at rest [m/s]
  double flow_speed = 0.0;      // m/s
  double first_dt = 0.0;        // s (the adaptive step at rest; the fixed step otherwise)
  double stable_dt = 0.0;       // s: the acoustic CFL limit (Courant number 1) at the expected speeds
  double steps = 0.0;
  double particle_steps = 0.0;
  double frames = 0.0;
  double output_bytes = 0.0;      // run.h5 and the CSV files
  double checkpoint_bytes = 0.0;  // one checkpoint.h5
};

RunCost predict_run_cost(const SceneDescription& scene);

}  // namespace bsmpm

// The hard-case harness (issue: hard cases stay numerically stable): runs a scene step by
// step and watches, over the whole run, what every hard case must keep:
//  - every particle field finite;
//  - the total mass exactly what it was (summed in id order: the same bits every step);
//  - every particle inside the tank;
//  - no fluid particle inside a solid by more than a stated fraction of a cell;
//  - rho/rho0 of the fluid within stated bounds;
//  - the total energy of the deformable bodies (conservation.hpp) never above its start plus
//    the work from outside (walls, clamps, rigid bodies) by more than a stated fraction of
//    the energy scale (the gravitational energy above the floor plus the initial kinetic
//    energy, or the work a rigid body put in, whichever is larger);
//  - the run finishing (a NumericalError is recorded, not thrown).
#pragma once

#include <string>
#include <vector>

#include "test_support.hpp"

namespace bsmpm::test {

struct HardCaseReport {
  bool finished = false;
  std::string error;              // the NumericalError that stopped the run, if any
  long steps = 0;
  double end_time = 0.0;
  bool finite = true;             // every field of every particle, every step
  bool mass_exact = true;         // the id-ordered sum, bit for bit
  bool inside_tank = true;
  long particles = 0;
  double cell = 0.0;              // smallest cell size [m]
  double min_density = 1e300, max_density = 0.0;  // fluid rho/rho0 over the run
  double max_penetration = 0.0;   // deepest fluid particle inside a solid [cells]
  double energy_scale = 0.0;      // J/m
  double max_energy_excess = -1e300;  // max of (E - E0 - W_external) / energy_scale
  double final_energy_change = 0.0;   // (E - E0) / energy_scale at the end
  double max_speed = 0.0;         // fluid, over the run [m/s]
  double max_displacement = 0.0;  // fluid, |x - x0| over the run [m]
  double dt_min = 1e300, dt_max = 0.0;
};

// Runs tests/hard/scenes/NAME with the overrides to its end time (or its first numerical
// error), checking every step. A `fixed_dt_factor` > 0 replaces the scene's time step by a
// fixed one, that many times the acoustic limit the cost prediction gives (run_cost.hpp).
HardCaseReport run_hard_case(const std::string& name, const std::vector<std::string>& overrides,
                             double fixed_dt_factor = 0.0);

// One line with every measure, for the log of a test and the margins in its comments.
std::string describe(const HardCaseReport& r);

}  // namespace bsmpm::test

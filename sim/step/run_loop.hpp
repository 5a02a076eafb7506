// Advances a simulation to its end time: chooses each time step, lands exactly on the
// frame times, reports progress and stops cleanly when asked to (Ctrl-C).
#pragma once

#include <functional>

#include "step/simulation.hpp"
#include "step/time_step.hpp"

namespace bsmpm {

struct RunProgress {
  long step = 0;
  double time = 0.0, end_time = 0.0, dt = 0.0;
  double steps_per_second = 0.0;
  double eta_seconds = 0.0;
  double wall_seconds = 0.0;
};

struct RunHooks {
  std::function<void(const Simulation&, double dt)> on_frame;      // at t = 0 and k * interval
  std::function<void(const RunProgress&)> on_progress;              // about once a second
  std::function<bool()> stop;                                       // true: stop after the current step
};

struct RunOutcome {
  bool interrupted = false;
  long steps = 0;
  double wall_seconds = 0.0;
  double min_dt = 0.0, max_dt = 0.0, last_dt = 0.0;
};

RunOutcome run_to_end(Simulation& sim, const TimeStepSettings& time, double frame_interval, const RunHooks& hooks);

}  // namespace bsmpm

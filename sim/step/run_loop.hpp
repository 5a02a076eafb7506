// Advances a simulation to its end time: chooses each time step, lands exactly on the
// frame times, reports progress and stops cleanly when asked to (Ctrl-C).
#pragma once

#include <functional>
#include <limits>

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

// Where the loop stands between two steps, over the whole run: a checkpoint holds it, so a
// resumed run lands on the same frame times and reports the same step range.
struct RunLoopState {
  bool started = false;  // the state at t = 0 is sampled and written
  long next_frame = 1;   // frame k lands at t = k * frame_interval
  long steps = 0;        // steps made since t = 0
  double min_dt = std::numeric_limits<double>::infinity(), max_dt = 0.0;  // frame landings left out
  double last_dt = 0.0;
};

struct RunHooks {
  std::function<void(const Simulation&, double dt)> on_frame;      // at t = 0 and k * interval
  std::function<void(const RunProgress&)> on_progress;              // after step 1, then about once a second
  std::function<bool()> stop;                                       // true: stop after the current step
  // After every step, its frame (if any) written: where checkpoints are taken.
  std::function<void(const Simulation&, const RunLoopState&)> after_step;
};

struct RunOutcome {
  bool interrupted = false;
  long steps = 0;             // made by this call
  double wall_seconds = 0.0;  // of this call
  double min_dt = 0.0, max_dt = 0.0, last_dt = 0.0;  // over the whole run
  RunLoopState state;         // where it stopped
};

// Runs from `state` (a fresh run, or a checkpoint's) to the end time or a stop.
RunOutcome run_to_end(Simulation& sim, const TimeStepSettings& time, double frame_interval, const RunHooks& hooks,
                      RunLoopState state = {});

}  // namespace bsmpm

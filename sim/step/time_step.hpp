// The time step: fixed (the paper uses 10 us), or adaptive from the CFL condition
// dt = C h_min / max_p (c_p + |v_p|), capped at a maximum.
#pragma once

#include <algorithm>

namespace bsmpm {

struct TimeStepSettings {
  enum class Mode { kFixed, kCfl };
  Mode mode = Mode::kCfl;
  double end = 1.0;        // end time [s]
  double dt = 1.0e-5;      // fixed step [s]
  double cfl = 0.3;        // Courant number
  double max_dt = 1.0e-3;  // cap of the adaptive step [s]
  // Reach each frame time in equal steps, none longer than the step above, instead of full
  // steps and a shortened last one: set for an incompressible fluid, whose pressure is an
  // impulse per step, so that a step much shorter than the one before reads as a spike
  // (docs/method.md §12). Off, the weakly compressible runs keep their steps.
  bool even_steps_to_frames = false;
};

inline double time_step(const TimeStepSettings& s, double max_signal_speed, double min_cell_size) {
  if (s.mode == TimeStepSettings::Mode::kFixed) return s.dt;
  if (max_signal_speed <= 0.0) return s.max_dt;
  return std::min(s.max_dt, s.cfl * min_cell_size / max_signal_speed);
}

}  // namespace bsmpm

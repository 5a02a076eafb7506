#include "step/run_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace bsmpm {

RunOutcome run_to_end(Simulation& sim, const TimeStepSettings& time, double frame_interval, const RunHooks& hooks,
                      RunLoopState state) {
  using clock = std::chrono::steady_clock;
  const GridInfo g = sim.grid_info();
  const double h_min = std::min(g.cell_size.x(), g.cell_size.y());
  const double tol = 1e-9 * std::min(frame_interval, time.end);
  RunOutcome out;

  if (!state.started) {
    sim.sample_probes();
    if (hooks.on_frame) hooks.on_frame(sim, 0.0);
    state.started = true;
  }
  const auto start = clock::now();
  const double start_time = sim.time();
  auto last_report = start;
  long steps_at_report = 0;
  while (sim.time() < time.end - tol) {
    if (hooks.stop && hooks.stop()) {
      out.interrupted = true;
      break;
    }
    double dt = time_step(time, sim.max_signal_speed(), h_min);
    // Land exactly on the next frame time (or the end).
    const double target = std::min(state.next_frame * frame_interval, time.end);
    const double remaining = target - sim.time();
    const bool landing = dt >= remaining * (1.0 - 1e-9);
    if (landing) dt = remaining;
    else if (time.even_steps_to_frames) dt = remaining / std::ceil(remaining / dt - 1e-9);
    state.last_dt = dt;
    sim.advance(dt);
    if (!landing) {  // the shortened steps that land on frame times say nothing of stability
      state.min_dt = std::min(state.min_dt, dt);
      state.max_dt = std::max(state.max_dt, dt);
    }
    ++state.steps;
    ++out.steps;
    if (std::abs(sim.time() - state.next_frame * frame_interval) <= tol) {
      if (hooks.on_frame) hooks.on_frame(sim, dt);
      ++state.next_frame;
    }
    if (hooks.after_step) hooks.after_step(sim, state);
    const auto now = clock::now();
    // After the first step (a log shows at once that the run is stepping, and how fast), then
    // about once a second.
    if (hooks.on_progress && (out.steps == 1 || now - last_report >= std::chrono::seconds(1))) {
      const double wall = std::chrono::duration<double>(now - start).count();
      const double window = std::chrono::duration<double>(now - last_report).count();
      RunProgress p;
      p.step = sim.step_count();
      p.time = sim.time();
      p.end_time = time.end;
      p.dt = dt;
      p.steps_per_second = window > 0.0 ? (out.steps - steps_at_report) / window : 0.0;
      const double sim_rate = wall > 0.0 ? (sim.time() - start_time) / wall : 0.0;  // simulated s per wall s
      p.eta_seconds = sim_rate > 0.0 ? (time.end - sim.time()) / sim_rate : 0.0;
      p.wall_seconds = wall;
      hooks.on_progress(p);
      last_report = now;
      steps_at_report = out.steps;
    }
  }
  out.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  out.last_dt = state.last_dt;
  out.min_dt = state.min_dt;
  out.max_dt = state.max_dt;
  if (out.min_dt > out.max_dt) out.min_dt = out.max_dt = state.last_dt;
  out.state = state;
  return out;
}

}  // namespace bsmpm

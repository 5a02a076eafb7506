#include "cli/run_driver.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "cli/commands.hpp"
#include "cli/interruption.hpp"
#include "cli/progress.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/version.hpp"
#include "io/run_summary.hpp"

namespace fs = std::filesystem;

namespace bsmpm::cli {

namespace {

RunSummary summarize(const RunContext& ctx, long steps, double wall_seconds) {
  RunSummary s;
  s.steps = steps;
  s.time = ctx.sim.time();
  s.end_time = ctx.scene.time.end;
  s.wall_seconds = wall_seconds;
  s.predicted_wall_seconds = ctx.predicted_wall_seconds;
  s.threads = ctx.threads;
  s.cores = static_cast<int>(std::thread::hardware_concurrency());
  s.particles = ctx.sim.particles().size();
  s.particle_steps_per_second = steps * static_cast<double>(s.particles) / std::max(wall_seconds, 1e-9);
  s.peak_memory_mb = peak_resident_memory_mb();
  s.frames = ctx.writer.frames_written();
  const PressureSolveStats& pressure = ctx.sim.stats().pressure;
  if (pressure.solves > 0) {
    s.pressure_solves = pressure.solves;
    s.pressure_iterations_mean = double(pressure.iterations) / pressure.solves;
    s.pressure_iterations_max = pressure.max_iterations;
    s.pressure_residual_max = pressure.max_residual;
  }
  s.program_version = kVersion;
  s.git_revision = kGitRevision;
  return s;
}

}  // namespace

int drive_run(RunContext& ctx, RunLoopState start) {
  Simulation& sim = ctx.sim;
  RunWriter& writer = ctx.writer;
  const bool tty = isatty(STDERR_FILENO);
  const double t_scale = ctx.scene.reference.time_factor();
  const auto started = std::chrono::steady_clock::now();
  auto wall = [&] {
    return ctx.previous_wall_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  RunLoopState last = start;  // the loop's state after the last completed step
  double last_time = sim.time();
  // The state checkpoint.h5 holds: a resumed run's starting point until it writes another.
  double checkpoint_time = start.started && fs::exists(checkpoint_path(ctx.dir)) ? sim.time() : std::nan("");
  // What checkpoints cost this session: how many, and the wall time spent writing them.
  int checkpoints = 0;
  double checkpoint_seconds = 0.0;
  auto checkpoint = [&](const fs::path& path, const RunLoopState& loop) {
    const auto begin = std::chrono::steady_clock::now();
    write_checkpoint(path.string(), ctx.checkpoint_scene, sim, loop, writer.state(sim), wall());
    ++checkpoints;
    checkpoint_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  };
  // Why the run stops for lack of room, found before anything was half-written: the run
  // stops after this step as if interrupted.
  std::string out_of_space;
  auto note_out_of_space = [&](const OutOfSpaceError& e) {
    if (!e.clean()) throw;
    out_of_space = e.what();
  };

  RunHooks hooks;
  hooks.stop = [&] { return interrupted() || !out_of_space.empty(); };
  hooks.on_frame = [&](const Simulation& s, double dt) { writer.write_frame(s, dt); };
  hooks.after_step = [&](const Simulation& s, const RunLoopState& loop) {
    last = loop;
    last_time = s.time();
    try {
      if (ctx.schedule.due(s)) {
        checkpoint(checkpoint_path(ctx.dir), loop);
        checkpoint_time = s.time();
      }
    } catch (const OutOfSpaceError& e) {
      note_out_of_space(e);
      return;
    }
    try {
      writer.keep_room(s);
    } catch (const OutOfSpaceError& e) {
      note_out_of_space(e);
    }
  };
  double last_line = -1e9;
  if (!ctx.quiet)
    hooks.on_progress = [&](const RunProgress& p) {
      if (!tty && p.wall_seconds - last_line < 10.0) return;
      last_line = p.wall_seconds;
      // The incompressible fluid's last pressure solve: its iterations and residual.
      const PressureSolve& solve = sim.last_step().pressure;
      const std::string pressure =
          solve.unknowns > 0 ? format("  p-solve %d it, res %.1e", solve.iterations, solve.residual) : "";
      std::fprintf(stderr, "%sstep %ld  t = %.5f s (T* %.2f, %3.0f%%)  dt = %.2e s%s  %.0f steps/s  ETA %s%s",
                   tty ? "\r" : "", p.step, p.time, p.time * t_scale, 100.0 * p.time / p.end_time, p.dt,
                   pressure.c_str(), p.steps_per_second, format_duration(p.eta_seconds).c_str(), tty ? "   " : "\n");
      std::fflush(stderr);
    };
  ctx.schedule.start(sim);
  catch_interruptions();

  auto end_line = [&] {
    if (tty && !ctx.quiet) std::fputc('\n', stderr);
  };
  auto write_summary = [&](const std::string& status, int exit_status, long steps) {
    RunSummary s = summarize(ctx, steps, wall());
    s.status = status;
    s.exit_status = exit_status;
    s.checkpoint_time = checkpoint_time;
    s.checkpoints = checkpoints;
    s.checkpoint_seconds = checkpoint_seconds;
    return s;
  };
  RunOutcome outcome;
  outcome.state = start;
  try {
    writer.keep_room(sim);  // the first frame (or, resumed, the next one)
  } catch (const OutOfSpaceError& e) {
    note_out_of_space(e);
  }
  try {
    if (out_of_space.empty()) outcome = run_to_end(sim, ctx.scene.time, ctx.scene.frame_interval, hooks, start);
    else outcome.interrupted = true;
  } catch (const NumericalError& e) {
    // The failing state as the last frame (to see where) and as a checkpoint (to load it);
    // checkpoint.h5, if any, stays the last good state.
    end_line();
    const std::string status = std::string("failed: ") + e.what();
    writer.write_frame(sim, sim.time() - last_time);
    checkpoint(failed_checkpoint_path(ctx.dir), last);
    writer.finish(status, sim, 0.0);
    write_run_summary(ctx.dir.string(), write_summary(status, kUnstable, sim.step_count()));
    std::fprintf(stderr,
                 "bsmpm: error: %s\nbsmpm: the %d frames written, the last one of the failing state, are in %s; that "
                 "state is also in %s\n",
                 e.what(), writer.frames_written(), writer.h5_path().c_str(),
                 failed_checkpoint_path(ctx.dir).string().c_str());
    return kUnstable;
  } catch (const std::exception& e) {
    // A write that failed half-way (an I/O error; or a full disk the room kept did not
    // foresee): the files say so where they still can; main reports the error.
    end_line();
    const bool full = dynamic_cast<const OutOfSpaceError*>(&e) != nullptr;
    const std::string status = std::string("failed: ") + (full ? "out of space: " : "") + e.what();
    try {
      writer.finish(status, sim, 0.0);
    } catch (const std::exception&) {
      // The file itself is what failed.
    }
    try {
      write_run_summary(ctx.dir.string(), write_summary(status, full ? kOutOfSpace : kFailure, sim.step_count()));
    } catch (const std::exception&) {
    }
    throw;
  }
  end_line();
  std::string checkpoint_note;  // why the stop wrote no checkpoint
  // Out of space: the room kept for the next frame goes to the checkpoint (tried again when
  // the periodic one did not fit).
  if (!out_of_space.empty()) writer.shrink_room(sim);
  if (outcome.interrupted) {
    try {
      checkpoint(checkpoint_path(ctx.dir), outcome.state);
      checkpoint_time = sim.time();
    } catch (const OutOfSpaceError& e) {
      if (!e.clean()) throw;
      checkpoint_note = e.what();
    }
  }
  const bool full = !out_of_space.empty();
  const int exit_status = full ? kOutOfSpace : outcome.interrupted ? interrupted_exit_status() : kOk;
  const std::string status =
      full ? "failed: out of space: " + out_of_space : outcome.interrupted ? "interrupted" : "completed";
  writer.finish(status, sim, outcome.last_dt);
  {
    RunSummary s = write_summary(status, exit_status, outcome.state.steps);
    s.min_dt = outcome.min_dt;
    s.max_dt = outcome.max_dt;
    write_run_summary(ctx.dir.string(), s);
  }
  if (!outcome.interrupted) {
    std::error_code ignored;
    fs::remove(checkpoint_path(ctx.dir), ignored);  // a completed run has nothing to resume
    // nor the half-written temporary of a checkpoint that a kill interrupted
    fs::remove(checkpoint_path(ctx.dir).string() + ".tmp", ignored);
  }

  const double steps_per_s = outcome.steps / std::max(outcome.wall_seconds, 1e-9);
  std::printf("%s  %ld steps in %.1f s: %.1f steps/s, %.3g particle-steps/s on %d threads; dt %.3g .. %.3g s\n",
              outcome.interrupted ? "stopped" : "done   ", outcome.steps, outcome.wall_seconds, steps_per_s,
              steps_per_s * sim.particles().size(), ctx.threads, outcome.min_dt, outcome.max_dt);
  if (const PressureSolveStats& ps = sim.stats().pressure; ps.solves > 0)
    std::printf("pressure %ld solves: %.1f iterations on average, at most %d; largest residual %.2g\n", ps.solves,
                double(ps.iterations) / ps.solves, ps.max_iterations, ps.max_residual);
  if (sim.stats().clamped_positions > 0)
    std::printf("note     %ld particle positions were pushed back inside the domain\n", sim.stats().clamped_positions);
  std::printf("wrote    %s (%d frames), %s/run.xdmf", writer.h5_path().c_str(), writer.frames_written(),
              ctx.dir.string().c_str());
  for (const auto& p : sim.probes()) std::printf(", %s/%s.csv", ctx.dir.string().c_str(), p->name().c_str());
  std::printf(", %s/conservation.csv, %s/summary.json\n", ctx.dir.string().c_str(), ctx.dir.string().c_str());
  if (checkpoints > 0)
    std::printf("checkpt  %d written in %.3g s, %.2g %% of the run's %.3g s\n", checkpoints, checkpoint_seconds,
                100.0 * checkpoint_seconds / std::max(outcome.wall_seconds, 1e-9), outcome.wall_seconds);
  std::fflush(stdout);
  const std::string resume = "bsmpm run --resume " + ctx.dir.string();
  if (full) {
    std::fprintf(stderr, "bsmpm: error: out of space: %s\n", out_of_space.c_str());
    const int frames = writer.frames_written();
    std::fprintf(stderr,
                 "bsmpm: the run stopped at t = %.6g s (step %ld) before writing anything it had no room for: %s, the "
                 "probe series and the conservation rows are whole and readable in %s\n",
                 sim.time(), sim.step_count(),
                 frames == 0 ? "no frame written"
                             : format("its %d frame%s (the last at t = %.6g s)", frames, frames == 1 ? "" : "s",
                                      writer.last_frame_time()).c_str(),
                 ctx.dir.string().c_str());
    if (checkpoint_note.empty())
      std::fprintf(stderr, "bsmpm: make room, then `%s` continues from t = %.6g s (the checkpoint it wrote)\n",
                   resume.c_str(), checkpoint_time);
    else if (std::isfinite(checkpoint_time))
      std::fprintf(stderr, "bsmpm: no room for a checkpoint of that state (%s); make room, then `%s` continues from "
                   "the last one, at t = %.6g s\n", checkpoint_note.c_str(), resume.c_str(), checkpoint_time);
    else
      std::fprintf(stderr, "bsmpm: no room for a checkpoint (%s): the run cannot be resumed\n", checkpoint_note.c_str());
    return kOutOfSpace;
  }
  if (outcome.interrupted) {
    std::fprintf(stderr,
                 "bsmpm: interrupted at t = %.5f s (step %ld); the frames written so far are kept, and %s continues "
                 "from here\n",
                 sim.time(), sim.step_count(), resume.c_str());
    return exit_status;
  }
  return kOk;
}

}  // namespace bsmpm::cli

#include "cli/run_driver.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "cli/commands.hpp"
#include "cli/interruption.hpp"
#include "cli/progress.hpp"
#include "core/error.hpp"
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
  auto checkpoint = [&](const fs::path& path, const RunLoopState& loop) {
    write_checkpoint(path.string(), ctx.checkpoint_scene, sim, loop, writer.state(sim), wall());
  };

  RunHooks hooks;
  hooks.stop = interrupted;
  hooks.on_frame = [&](const Simulation& s, double dt) { writer.write_frame(s, dt); };
  hooks.after_step = [&](const Simulation& s, const RunLoopState& loop) {
    last = loop;
    last_time = s.time();
    if (ctx.schedule.due(s)) checkpoint(checkpoint_path(ctx.dir), loop);
  };
  double last_line = -1e9;
  if (!ctx.quiet)
    hooks.on_progress = [&](const RunProgress& p) {
      if (!tty && p.wall_seconds - last_line < 10.0) return;
      last_line = p.wall_seconds;
      std::fprintf(stderr, "%sstep %ld  t = %.5f s (T* %.2f, %3.0f%%)  dt = %.2e s  %.0f steps/s  ETA %s%s",
                   tty ? "\r" : "", p.step, p.time, p.time * t_scale, 100.0 * p.time / p.end_time, p.dt,
                   p.steps_per_second, format_duration(p.eta_seconds).c_str(), tty ? "   " : "\n");
      std::fflush(stderr);
    };
  ctx.schedule.start(sim);
  catch_interruptions();

  auto end_line = [&] {
    if (tty && !ctx.quiet) std::fputc('\n', stderr);
  };
  auto write_failure_summary = [&](const std::string& status, int exit_status) {
    RunSummary s = summarize(ctx, sim.step_count(), wall());
    s.status = status;
    s.exit_status = exit_status;
    write_run_summary(ctx.dir.string(), s);
  };
  RunOutcome outcome;
  try {
    outcome = run_to_end(sim, ctx.scene.time, ctx.scene.frame_interval, hooks, start);
  } catch (const NumericalError& e) {
    // The failing state as the last frame (to see where) and as a checkpoint (to load it);
    // checkpoint.h5, if any, stays the last good state.
    end_line();
    const std::string status = std::string("failed: ") + e.what();
    writer.write_frame(sim, sim.time() - last_time);
    checkpoint(failed_checkpoint_path(ctx.dir), last);
    writer.finish(status, sim, 0.0);
    write_failure_summary(status, kUnstable);
    std::fprintf(stderr,
                 "bsmpm: error: %s\nbsmpm: the %d frames written, the last one of the failing state, are in %s; that "
                 "state is also in %s\n",
                 e.what(), writer.frames_written(), writer.h5_path().c_str(),
                 failed_checkpoint_path(ctx.dir).string().c_str());
    return kUnstable;
  } catch (const std::exception& e) {
    // A failed write (disk full, ...): the file says so instead of "running"; the frames
    // flushed before it stay readable.
    end_line();
    try {
      writer.finish(std::string("failed: ") + e.what(), sim, 0.0);
      write_failure_summary(std::string("failed: ") + e.what(), kFailure);
    } catch (const std::exception&) {
      // The file itself is what failed; main reports the first error.
    }
    throw;
  }
  end_line();
  if (outcome.interrupted) checkpoint(checkpoint_path(ctx.dir), outcome.state);
  writer.finish(outcome.interrupted ? "interrupted" : "completed", sim, outcome.last_dt);
  {
    RunSummary s = summarize(ctx, outcome.state.steps, wall());
    s.status = outcome.interrupted ? "interrupted" : "completed";
    s.exit_status = outcome.interrupted ? kInterrupted : kOk;
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
  if (sim.stats().clamped_positions > 0)
    std::printf("note     %ld particle positions were pushed back inside the domain\n", sim.stats().clamped_positions);
  std::printf("wrote    %s (%d frames), %s/run.xdmf", writer.h5_path().c_str(), writer.frames_written(),
              ctx.dir.string().c_str());
  for (const auto& p : sim.probes()) std::printf(", %s/%s.csv", ctx.dir.string().c_str(), p->name().c_str());
  std::printf(", %s/conservation.csv, %s/summary.json\n", ctx.dir.string().c_str(), ctx.dir.string().c_str());
  if (outcome.interrupted) {
    std::fprintf(stderr,
                 "bsmpm: interrupted at t = %.5f s (step %ld); the frames written so far are kept, and "
                 "bsmpm run --resume %s continues from here\n",
                 sim.time(), sim.step_count(), ctx.dir.string().c_str());
    return kInterrupted;
  }
  return kOk;
}

}  // namespace bsmpm::cli

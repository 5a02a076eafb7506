// bsmpm run SCENE --out DIR: simulates a scene, writing DIR/run.h5, DIR/run.xdmf and one CSV
// per probe. Frames are flushed as they are written; Ctrl-C stops after the current step and
// keeps everything written so far.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/interruption.hpp"
#include "cli/progress.hpp"
#include "cli/scene_summary.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "io/run_summary.hpp"
#include "io/run_writer.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "settings/render_options.hpp"
#include "step/run_loop.hpp"

namespace fs = std::filesystem;

namespace bsmpm::cli {

namespace {

const char* kHelp =
    "usage: bsmpm run SCENE.toml --out DIR [options]\n"
    "\n"
    "Simulates the scene and writes\n"
    "  DIR/run.h5      frames (particle position, velocity, pressure, stress, displacement,\n"
    "                  volume), probe series, grid, bodies and provenance (docs/output-format.md)\n"
    "  DIR/run.xdmf    the frames for ParaView\n"
    "  DIR/NAME.csv    one table per probe, with a header row\n"
    "  DIR/summary.json  steps, wall time, threads, particles, peak memory, exit status\n"
    "\n"
    "options\n"
    "  --out DIR          output directory (created; must not hold another run)\n"
    "  --set KEY=VALUE    override a scene value, e.g. --set grid.cell_size=0.008\n"
    "                     (repeatable; VALUE is TOML, a bare word is a string)\n"
    "  --threads N        OpenMP threads (default: all cores); results do not depend on N\n"
    "  --force            replace the run already in DIR\n"
    "  --quiet            no progress line\n"
    "\n"
    "exit status: 0 done, 2 bad scene or usage, 3 numerical instability (frames kept),\n"
    "130 interrupted (frames kept), 1 other failure\n";

// Refuses to overwrite another run; with --force removes the files a run writes.
void prepare_directory(const fs::path& dir, bool force) {
  if (!fs::exists(dir)) return;
  if (!fs::is_directory(dir)) throw UsageError(dir.string() + " exists and is not a directory");
  const bool has_run = fs::exists(dir / "run.h5");
  const bool empty = fs::is_empty(dir);
  if (!force && has_run) throw UsageError(dir.string() + " holds a run already (run.h5); pass --force to replace it");
  if (!force && !empty) throw UsageError(dir.string() + " is not empty; choose a new directory or pass --force");
  if (force) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      const auto name = entry.path().filename();
      if (name == "run.h5" || name == "run.xdmf" || ext == ".csv" || name == "run.xdmf.tmp" ||
          name == "summary.json") fs::remove(entry.path());
    }
  }
}

// The summary of a run that ended (or stopped) after `steps` steps.
RunSummary summarize(const Simulation& sim, const RunWriter& writer, const SceneDescription& scene, int threads,
                     long steps, double wall_seconds) {
  RunSummary s;
  s.steps = steps;
  s.time = sim.time();
  s.end_time = scene.time.end;
  s.wall_seconds = wall_seconds;
  s.threads = threads;
  s.cores = static_cast<int>(std::thread::hardware_concurrency());
  s.particles = sim.particles().size();
  s.particle_steps_per_second = steps * static_cast<double>(s.particles) / std::max(wall_seconds, 1e-9);
  s.peak_memory_mb = peak_resident_memory_mb();
  s.frames = writer.frames_written();
  s.program_version = kVersion;
  s.git_revision = kGitRevision;
  return s;
}

}  // namespace

int command_run(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help", "--force", "--quiet"}, {"--out", "--threads"}, {"--set"});
  if (args.flag("--help")) {
    std::fputs(kHelp, stdout);
    return kOk;
  }
  if (args.positional().size() != 1) throw UsageError("run expects one scene file (see bsmpm run --help)");
  if (!args.has("--out")) throw UsageError("run needs --out DIR (see bsmpm run --help)");
  const int threads = apply_thread_option(args);

  // Validate and build everything before touching the disk: a bad scene leaves nothing.
  const SceneDescription scene = load_scene(args.positional()[0], args.all("--set"), {render::render_scene_extension()});
  auto sim = build_simulation(scene);
  const fs::path dir = args.option("--out");
  prepare_directory(dir, args.flag("--force"));
  print_scene_summary(stdout, scene, *sim, threads);

  RunProvenance prov;
  prov.title = scene.title;
  prov.scene_path = scene.path;
  prov.scene_text = scene.source_text;
  prov.effective_scene = scene.effective_text;
  prov.command_line = "bsmpm run";
  for (const auto& a : argv) prov.command_line += " " + a;
  prov.threads = threads;
  prov.end_time = scene.time.end;
  prov.reference = scene.reference;

  const bool created = !fs::exists(dir);
  fs::create_directories(dir);
  std::unique_ptr<RunWriter> writer;
  try {
    writer = std::make_unique<RunWriter>(dir.string(), prov, *sim);
  } catch (...) {
    if (created) fs::remove_all(dir);
    throw;
  }

  const bool tty = isatty(STDERR_FILENO);
  const double t_scale = scene.reference.time_factor();
  RunHooks hooks;
  hooks.stop = interrupted;
  hooks.on_frame = [&](const Simulation& s, double dt) { writer->write_frame(s, dt); };
  double last_line = -1e9;
  if (!args.flag("--quiet"))
    hooks.on_progress = [&](const RunProgress& p) {
      if (!tty && p.wall_seconds - last_line < 10.0) return;
      last_line = p.wall_seconds;
      std::fprintf(stderr, "%sstep %ld  t = %.5f s (T* %.2f, %3.0f%%)  dt = %.2e s  %.0f steps/s  ETA %s%s",
                   tty ? "\r" : "", p.step, p.time, p.time * t_scale, 100.0 * p.time / p.end_time, p.dt,
                   p.steps_per_second, format_duration(p.eta_seconds).c_str(), tty ? "   " : "\n");
      std::fflush(stderr);
    };
  catch_interruptions();

  RunOutcome outcome;
  const auto started = std::chrono::steady_clock::now();
  // A failed run's summary: the steps it made and its wall time, no time-step range.
  auto write_failure_summary = [&](const std::string& status, int exit_status) {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    RunSummary s = summarize(*sim, *writer, scene, threads, sim->step_count(), wall);
    s.status = status;
    s.exit_status = exit_status;
    write_run_summary(dir.string(), s);
  };
  try {
    outcome = run_to_end(*sim, scene.time, scene.frame_interval, hooks);
  } catch (const NumericalError& e) {
    if (tty && !args.flag("--quiet")) std::fputc('\n', stderr);
    writer->finish(std::string("failed: ") + e.what(), *sim, 0.0);
    write_failure_summary(std::string("failed: ") + e.what(), kUnstable);
    std::fprintf(stderr, "bsmpm: error: %s\nbsmpm: the %d frames written before the failure are in %s\n", e.what(),
                 writer->frames_written(), writer->h5_path().c_str());
    return kUnstable;
  } catch (const std::exception& e) {
    // A failed write (disk full, ...): the file says so instead of "running"; the frames
    // flushed before it stay readable.
    if (tty && !args.flag("--quiet")) std::fputc('\n', stderr);
    try {
      writer->finish(std::string("failed: ") + e.what(), *sim, 0.0);
      write_failure_summary(std::string("failed: ") + e.what(), kFailure);
    } catch (const std::exception&) {
      // The file itself is what failed; main reports the first error.
    }
    throw;
  }
  if (tty && !args.flag("--quiet")) std::fputc('\n', stderr);
  writer->finish(outcome.interrupted ? "interrupted" : "completed", *sim, outcome.last_dt);
  {
    RunSummary s = summarize(*sim, *writer, scene, threads, outcome.steps, outcome.wall_seconds);
    s.status = outcome.interrupted ? "interrupted" : "completed";
    s.exit_status = outcome.interrupted ? kInterrupted : kOk;
    s.min_dt = outcome.min_dt;
    s.max_dt = outcome.max_dt;
    write_run_summary(dir.string(), s);
  }

  const double steps_per_s = outcome.steps / std::max(outcome.wall_seconds, 1e-9);
  std::printf("%s  %ld steps in %.1f s: %.1f steps/s, %.3g particle-steps/s on %d threads; dt %.3g .. %.3g s\n",
              outcome.interrupted ? "stopped" : "done   ", outcome.steps, outcome.wall_seconds, steps_per_s,
              steps_per_s * sim->particles().size(), threads, outcome.min_dt, outcome.max_dt);
  if (sim->stats().clamped_positions > 0)
    std::printf("note     %ld particle positions were pushed back inside the domain\n", sim->stats().clamped_positions);
  std::printf("wrote    %s (%d frames), %s/run.xdmf", writer->h5_path().c_str(), writer->frames_written(),
              dir.string().c_str());
  for (const auto& p : sim->probes()) std::printf(", %s/%s.csv", dir.string().c_str(), p->name().c_str());
  std::printf(", %s/summary.json\n", dir.string().c_str());
  if (outcome.interrupted) {
    std::fprintf(stderr, "bsmpm: interrupted at t = %.5f s; the frames written so far are kept\n", sim->time());
    return kInterrupted;
  }
  return kOk;
}

}  // namespace bsmpm::cli

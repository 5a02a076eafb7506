// bsmpm run SCENE --out DIR: simulates a scene, writing DIR/run.h5, DIR/run.xdmf, one CSV
// per probe and conservation.csv. Frames are flushed as they are written; Ctrl-C stops after
// the current step, keeps everything written so far and writes a checkpoint, from which
// bsmpm run --resume DIR continues bit for bit.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/arguments.hpp"
#include "cli/checkpoint_schedule.hpp"
#include "cli/progress.hpp"
#include "cli/commands.hpp"
#include "cli/run_driver.hpp"
#include "cli/scene_summary.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/version.hpp"
#include "io/run_reader.hpp"
#include "scene/run_guards.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "settings/render_options.hpp"
#include "step/effects/gravity.hpp"

namespace fs = std::filesystem;

namespace bsmpm::cli {

namespace {

const char* kHelp =
    "usage: bsmpm run SCENE.toml --out DIR [options]\n"
    "       bsmpm run --resume DIR [--threads N] [--quiet] [--checkpoint-every EVERY]\n"
    "\n"
    "Simulates the scene and writes\n"
    "  DIR/run.h5      frames (particle position, velocity, pressure, stress, displacement,\n"
    "                  volume), probe series, conservation series, grid, bodies and provenance\n"
    "                  (docs/output-format.md)\n"
    "  DIR/run.xdmf    the frames for ParaView\n"
    "  DIR/NAME.csv    one table per probe, with a header row\n"
    "  DIR/conservation.csv  mass, momentum, energies and the work of walls and contact per frame\n"
    "  DIR/summary.json  steps, wall time (and the predicted one), threads, particles, peak\n"
    "                  memory, exit status\n"
    "  DIR/checkpoint.h5  the state to resume from (every 10 minutes, and when stopped)\n"
    "\n"
    "Before anything is built, the run's cost is predicted (and its wall time, from the rates\n"
    "`bsmpm bench` recorded); a run that would not fit in memory or on the disk, or whose time\n"
    "step is absurdly small, is refused (exit 2).\n"
    "\n"
    "options\n"
    "  --out DIR          output directory (created; must not hold another run)\n"
    "  --set KEY=VALUE    override a scene value, e.g. --set grid.cell_size=0.008\n"
    "                     (repeatable; VALUE is TOML, a bare word is a string)\n"
    "  --threads N        OpenMP threads (default: all cores); results do not depend on N\n"
    "  --checkpoint-every EVERY  write DIR/checkpoint.h5 every EVERY of wall-clock time (10min,\n"
    "                     1h), of simulated time (0.05s) or steps (2000steps); 0: never.\n"
    "                     Default: 10min, or $BSMPM_CHECKPOINT_EVERY (a site's default), so that\n"
    "                     a run killed without warning loses at most that much; Ctrl-C, SIGTERM\n"
    "                     and a full disk always write one\n"
    "  --resume DIR       continue the run in DIR from its checkpoint: frames and probe rows\n"
    "                     written after it are replaced; the result is the same, bit for bit,\n"
    "                     as a run never interrupted\n"
    "  --force            replace the run already in DIR; and start even when the predicted\n"
    "                     output does not fit on DIR's disk (the run then stops, resumable,\n"
    "                     when the disk is full), or when it is predicted to take more\n"
    "                     than a month\n"
    "  --quiet            no progress line\n"
    "\n"
    "exit status: 0 done, 2 bad scene or usage or a run too large, 3 numerical instability\n"
    "(frames kept, the failing state in DIR/checkpoint_failed.h5), 4 out of space (frames\n"
    "kept; resumable when a checkpoint fit), 130 interrupted by Ctrl-C and 143 by SIGTERM\n"
    "(frames kept, resumable), 1 other failure\n";

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
      const std::string name = entry.path().filename().string();
      if (name == "run.h5" || name == "run.xdmf" || ext == ".csv" || name == "run.xdmf.tmp" ||
          name == "summary.json" || name.rfind("checkpoint", 0) == 0)
        fs::remove(entry.path());
    }
  }
}

// When checkpoints come and what they cost on the disk (their time: summary.json).
void print_checkpoint_plan(const fs::path& dir, const CheckpointSchedule& schedule, const RunCost& cost,
                           const WallTimeEstimate& wall) {
  if (!schedule.enabled()) {
    std::printf("checkpt  none (--checkpoint-every 0): a run killed without warning starts again from its last "
                "checkpoint, if any\n");
    return;
  }
  std::string expected;
  if (schedule.unit() == CheckpointSchedule::Unit::kWallSeconds && std::isfinite(wall.seconds)) {
    const double n = std::floor(wall.seconds / schedule.every());
    expected = n < 1.0 ? format("; none in the predicted %s", format_duration(wall.seconds).c_str())
                       : format("; about %.0f in the predicted %s", n, format_duration(wall.seconds).c_str());
  }
  std::printf("checkpt  %s to %s, about %s each (the last one kept, replaced whole)%s; --checkpoint-every 0: "
              "none\n",
              schedule.describe().c_str(), (dir / "checkpoint.h5").string().c_str(),
              format_bytes(cost.checkpoint_bytes).c_str(), expected.c_str());
}

Vec2 gravity_of(const SceneDescription& scene) {
  const auto* g = scene.effect_parameters<GravityParameters>();
  return g ? g->vector() : Vec2::Zero();
}

std::string command_line(const std::vector<std::string>& argv) {
  std::string line = "bsmpm run";
  for (const auto& a : argv) line += " " + a;
  return line;
}

// The checkpoint's particles are this scene's: same count, each body's range holding its
// own particles, every id once.
void check_particles(const Particles& ps, const Simulation& sim, const std::string& path) {
  const auto& bodies = sim.bodies();
  bool ok = ps.size() == sim.particles().size();
  std::vector<char> seen(ps.size(), 0);
  for (std::size_t b = 0; ok && b < bodies.size(); ++b)
    for (std::size_t p = bodies[b].begin; ok && p < bodies[b].end; ++p) {
      ok = ps.body[p] == b && ps.id[p] < ps.size() && !seen[ps.id[p]] && sim.particles().body[sim.index_of_id()[ps.id[p]]] == b;
      if (ok) seen[ps.id[p]] = 1;
    }
  if (!ok) throw IoError(path + ": its particles are not those of its scene");
}

int resume_run(const Arguments& args, const std::vector<std::string>& argv, int threads,
               const CheckpointSchedule& schedule) {
  if (!args.positional().empty() || !args.all("--set").empty() || args.has("--out") || args.flag("--force"))
    throw UsageError("--resume DIR takes the scene and its overrides from the checkpoint: give no scene, --set, "
                     "--out or --force");
  const fs::path dir = args.option("--resume");
  const fs::path path = checkpoint_path(dir);
  if (!fs::exists(path)) {
    if (fs::exists(dir / "run.h5") && RunReader((dir / "run.h5").string()).status() == "completed")
      throw UsageError("the run in " + dir.string() + " is completed: nothing to resume");
    throw UsageError(dir.string() + " holds no checkpoint.h5 to resume from (a run writes one when stopped, and "
                     "every --checkpoint-every)");
  }
  Checkpoint c = read_checkpoint(path.string());
  if (c.program_version != kVersion || c.git_revision != kGitRevision)
    std::fprintf(stderr, "bsmpm: warning: the checkpoint was written by bsmpm %s (%s), this is %s (%s): the resumed "
                 "run may differ from one never interrupted\n", c.program_version.c_str(), c.git_revision.c_str(),
                 kVersion, kGitRevision);
  const SceneDescription scene =
      load_scene_text(c.scene.text, c.scene.path, c.scene.overrides, {render::render_scene_extension()});
  const RunCost cost = predict_run_cost(scene);
  const auto warnings = check_run_cost(scene, cost, machine_resources(""), schedule.enabled());
  auto sim = build_simulation(scene);
  check_particles(c.particles, *sim, path.string());
  if (c.probes.size() != sim->probes().size()) throw IoError(path.string() + ": its probes are not those of its scene");
  sim->restore(std::move(c.particles), c.counters, c.probes);
  print_scene_summary(stdout, scene, *sim, threads);
  const WallTimeEstimate wall = estimate_wall_time(scene, cost, threads);
  print_run_cost(stdout, cost, warnings, wall);
  std::printf("resume   %s at step %ld, t = %.6g s (frame %ld)\n", dir.string().c_str(), sim->step_count(),
              sim->time(), c.writer.frames);
  RunWriter writer(dir.string(), c.writer, gravity_of(scene), *sim);
  RunContext ctx{scene, *sim, writer, dir, threads, args.flag("--quiet"), {}, c.scene, c.wall_seconds};
  ctx.schedule = schedule;
  print_checkpoint_plan(dir, schedule, cost, wall);
  ctx.predicted_wall_seconds = wall.seconds;
  ctx.checkpoint_scene.command_line += "; " + command_line(argv);
  return drive_run(ctx, c.loop);
}

}  // namespace

int command_run(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help", "--force", "--quiet"}, {"--out", "--threads", "--resume", "--checkpoint-every"},
                 {"--set"});
  if (args.help(kHelp)) return kOk;
  const int threads = apply_thread_option(args);
  const std::string every = args.option("--checkpoint-every");
  const CheckpointSchedule schedule = CheckpointSchedule::chosen(args.has("--checkpoint-every") ? &every : nullptr);
  if (args.has("--resume")) return resume_run(args, argv, threads, schedule);
  if (args.positional().size() != 1) throw UsageError("run expects one scene file (see bsmpm run --help)");
  if (!args.has("--out")) throw UsageError("run needs --out DIR (see bsmpm run --help)");
  const fs::path dir = args.option("--out");

  // Validate, predict and build everything before touching the disk: a bad scene, or one
  // too large for this machine, leaves nothing.
  const SceneDescription scene = load_scene(args.positional()[0], args.all("--set"), {render::render_scene_extension()});
  const RunCost cost = predict_run_cost(scene);
  auto warnings =
      check_run_cost(scene, cost, machine_resources(dir.string()), schedule.enabled(), args.flag("--force"));
  const WallTimeEstimate wall = estimate_wall_time(scene, cost, threads);
  for (const std::string& w : check_wall_time(scene, wall, args.flag("--force"))) warnings.push_back(w);
  auto sim = build_simulation(scene);
  prepare_directory(dir, args.flag("--force"));
  print_scene_summary(stdout, scene, *sim, threads);
  print_run_cost(stdout, cost, warnings, wall);
  print_checkpoint_plan(dir, schedule, cost, wall);

  RunProvenance prov;
  prov.title = scene.title;
  prov.scene_path = scene.path;
  prov.scene_text = scene.source_text;
  prov.effective_scene = scene.effective_text;
  prov.command_line = command_line(argv);
  prov.threads = threads;
  prov.end_time = scene.time.end;
  prov.reference = scene.reference;
  prov.gravity = gravity_of(scene);

  const bool created = !fs::exists(dir);
  fs::create_directories(dir);
  std::unique_ptr<RunWriter> writer;
  try {
    writer = std::make_unique<RunWriter>(dir.string(), prov, *sim);
  } catch (...) {
    if (created) fs::remove_all(dir);
    throw;
  }
  RunContext ctx{scene, *sim, *writer, dir, threads, args.flag("--quiet"), schedule,
                 CheckpointScene{scene.path, scene.source_text, args.all("--set"), prov.command_line}, 0.0};
  ctx.predicted_wall_seconds = wall.seconds;
  return drive_run(ctx, RunLoopState{});
}

}  // namespace bsmpm::cli

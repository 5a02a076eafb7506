// bsmpm bench SCENE: times the step of a scene (no output files) and reports time per step
// and particle-steps per second with the thread and core counts, the time of each phase of
// the step (step/phase_timer.hpp) and the solver's memory per particle and per control point.
// Every run also records its rate in this machine's calibration file (scene/calibration_file.hpp),
// from which `bsmpm check` and `bsmpm run` predict the wall time of a run.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <thread>
#include <utility>
#include <vector>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "io/json.hpp"
#include "scene/calibration_file.hpp"
#include "scene/run_cost.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "step/phase_timer.hpp"
#include "step/time_step.hpp"

namespace bsmpm::cli {

namespace {

const char* kHelp =
    "usage: bsmpm bench SCENE.toml [--steps N] [--warmup N] [--threads N] [--set KEY=VALUE ...] [--json]\n"
    "\n"
    "Builds the scene, runs --warmup steps (default 20), then times --steps steps (default 200)\n"
    "with the scene's time step. Prints time per step and particle-steps per second, with the\n"
    "thread count and the machine's core count; the time per step of each phase of the step\n"
    "(\"outside\" is the bench loop between steps, \"other\" the step outside every phase); and\n"
    "the solver's heap bytes per particle and per control point. --json prints one JSON object\n"
    "instead (a record for scripts/bench --compare).\n"
    "\n"
    "The rate is also recorded in this machine's calibration file ($BSMPM_CALIBRATION, else\n"
    "$XDG_CACHE_HOME/bsmpm/calibration.json, else ~/.cache/bsmpm/calibration.json), one record per\n"
    "machine, thread count and scene features (spline order, materials, fluid volume, velocity\n"
    "update, shifting, grid fields), the newest kept; `bsmpm check` and `bsmpm run` predict a\n"
    "run's wall time from it.\n";

// How idle OpenMP threads wait: as the environment says; main.cpp sets GOMP_SPINCOUNT=1000
// when it says nothing (or, should that have failed, libgomp spins for a while: "default").
std::string omp_wait_policy() {
  if (const char* policy = std::getenv("OMP_WAIT_POLICY")) return policy;
  if (const char* spin = std::getenv("GOMP_SPINCOUNT")) return std::string("GOMP_SPINCOUNT=") + spin;
  return "default";
}

// The phases with any time, in step order, as (name, seconds per step).
std::vector<std::pair<const char*, double>> phase_table(const PhaseTimer& timer, long steps) {
  std::vector<std::pair<const char*, double>> rows;
  for (std::size_t k = 0; k < kStepPhaseCount; ++k)
    if (timer.seconds(k) > 0.0) rows.emplace_back(kStepPhaseNames[k], timer.seconds(k) / steps);
  return rows;
}

// Adds the measured rate to the calibration file; a failure is a warning (the measurement
// stands). Says where it went unless the output is a JSON record.
void record_rate(const SceneDescription& scene, const Simulation& sim, int threads, double rate, bool quiet) {
  if (sim.particles().size() == 0 || !(rate > 0.0)) return;  // nothing measured
  CalibrationRecord r;
  r.machine = this_machine();
  r.threads = threads;
  r.features = rate_features(scene, predict_run_cost(scene));
  r.particle_steps_per_second = rate;
  r.particles = static_cast<double>(sim.particles().size());
  for (const Body& b : sim.bodies())
    if (is_rigid(b.material)) r.rigid_particles += static_cast<double>(b.size());
  r.scene = scene.path;
  r.recorded_at = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  r.program_version = kVersion;
  const std::string path = calibration_path();
  try {
    const std::string warning = record_calibration(path, r);
    if (!warning.empty()) std::fprintf(stderr, "bsmpm: warning: %s\n", warning.c_str());
    if (!quiet) std::printf("calibration          recorded in %s\n", path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bsmpm: warning: the rate is not recorded: %s\n", e.what());
  }
}
}  // namespace

int command_bench(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help", "--json"}, {"--steps", "--warmup", "--threads"}, {"--set"});
  if (args.help(kHelp)) return kOk;
  if (args.positional().size() != 1) throw UsageError("bench expects one scene file (see bsmpm bench --help)");
  const long steps = args.integer("--steps", 200), warmup = args.integer("--warmup", 20);
  if (steps < 1 || warmup < 0) throw UsageError("--steps must be >= 1 and --warmup >= 0");
  const int threads = apply_thread_option(args);
  const SceneDescription scene = load_scene(args.positional()[0], args.all("--set"));
  auto sim = build_simulation(scene);
  const GridInfo g = sim->grid_info();
  const double h_min = std::min(g.cell_size.x(), g.cell_size.y());
  auto step = [&] { sim->advance(time_step(scene.time, sim->max_signal_speed(), h_min)); };
  for (long i = 0; i < warmup; ++i) step();
  PhaseTimer timer;
  sim->set_phase_timer(&timer);
  const auto t0 = std::chrono::steady_clock::now();
  timer.reset(StepPhase::kOutside);
  for (long i = 0; i < steps; ++i) step();
  timer.switch_to(StepPhase::kOutside);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sim->set_phase_timer(nullptr);
  const auto phases = phase_table(timer, steps);
  const MemoryUse mem = sim->memory_use();
  const double per_particle = mem.particles ? double(mem.particle_bytes) / mem.particles : 0.0;
  const double per_node = mem.control_points ? double(mem.grid_bytes) / mem.control_points : 0.0;
  const std::size_t n = sim->particles().size();
  const double per_step = wall / steps;
  const double rate = n * steps / wall;
  const unsigned cores = std::thread::hardware_concurrency();
  const std::string wait_policy = omp_wait_policy();
  if (args.flag("--json")) {
    std::string overrides;
    for (const std::string& o : args.all("--set")) overrides += (overrides.empty() ? "" : ", ") + json_quoted(o);
    std::printf("{\"scene\": %s, \"overrides\": [%s], \"particles\": %zu, \"order\": %d, \"cells\": [%d, %d], \"cell_size\": [%g, %g], "
                "\"threads\": %d, \"cores\": %u, \"omp_wait_policy\": %s, \"steps\": %ld, \"seconds\": %.6g, \"seconds_per_step\": %.6g, "
                "\"particle_steps_per_second\": %.6g, \"control_points\": %zu, \"bytes_per_particle\": %.6g, "
                "\"bytes_per_control_point\": %.6g, \"phase_seconds_per_step\": {",
                json_quoted(scene.path).c_str(), overrides.c_str(), n, g.order, g.cells_x, g.cells_y, g.cell_size.x(), g.cell_size.y(),
                threads, cores, json_quoted(wait_policy).c_str(), steps, wall, per_step, rate, mem.control_points, per_particle, per_node);
    for (std::size_t k = 0; k < phases.size(); ++k)
      std::printf("%s\"%s\": %.6g", k ? ", " : "", phases[k].first, phases[k].second);
    std::printf("}}\n");
  } else {
    std::printf("scene                %s\n", scene.path.c_str());
    std::printf("grid                 %d x %d cells of %.4g mm, order %d\n", g.cells_x, g.cells_y, g.cell_size.x() * 1e3,
                g.order);
    std::printf("particles            %zu\n", n);
    std::printf("threads / cores      %d / %u (waiting %s)\n", threads, cores, wait_policy.c_str());
    std::printf("steps timed          %ld (after %ld warm-up)\n", steps, warmup);
    std::printf("time per step        %.3f ms\n", per_step * 1e3);
    std::printf("particle-steps/s     %.3g\n", rate);
    std::printf("memory               %.0f bytes per particle, %.0f per control point (%zu)\n", per_particle,
                per_node, mem.control_points);
    std::printf("phase                ms/step   share\n");
    for (const auto& [name, seconds] : phases)
      std::printf("  %-18s %8.3f  %5.1f %%\n", name, seconds * 1e3, 100.0 * seconds / per_step);
  }
  std::fflush(stdout);
  record_rate(scene, *sim, threads, rate, args.flag("--json"));
  return kOk;
}

}  // namespace bsmpm::cli

// bsmpm check SCENE [--set KEY=VALUE ...]: validates a scene and prints what a run would do.
#include <cstdio>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/scene_summary.hpp"
#include "cli/wall_time_estimate.hpp"
#include "core/error.hpp"
#include "scene/run_guards.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "settings/render_options.hpp"

namespace bsmpm::cli {

namespace {

// Above this many particles check does not seed the scene (unless --build): seeding runs at
// about half a million particles a second (the elastic gate at 0.1 mm, 17.4 million
// particles: 34 s), and check answers from the description in well under a second.
constexpr double kCheckSeedsUpTo = 1.0e6;

const char* kHelp =
    "usage: bsmpm check SCENE.toml [--set KEY=VALUE ...] [--out DIR] [--build]\n"
    "\n"
    "Validates the scene (every key, type and range), predicts what a run would cost (particles,\n"
    "steps, memory, output size, and the wall time on this machine from the rates `bsmpm bench`\n"
    "recorded), builds it, and prints the grid, bodies, time step and active effects. Writes\n"
    "nothing. A scene that would not fit in memory (or, with --out DIR, whose output would not\n"
    "fit on that disk), whose time step is absurdly small, or that is predicted to take more\n"
    "than a month, is refused (exit 2) before anything is built. A scene of more than a million\n"
    "particles is not built (seeding them takes seconds): the prediction is the answer.\n"
    "\n"
    "options\n"
    "  --set KEY=VALUE   override a scene value (repeatable)\n"
    "  --out DIR         also check the free space where the run would write (else the current\n"
    "                    directory's, a warning only)\n"
    "  --build           build a scene of more than a million particles too\n"
    "  --threads N       OpenMP threads for building, and of the run whose wall time is predicted\n"
    "\n"
    "exit status: 0 the scene can run, 2 bad scene or usage or a run refused, 1 other failure\n";
}  // namespace

int command_check(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help", "--build"}, {"--threads", "--out"}, {"--set"});
  if (args.help(kHelp)) return kOk;
  if (args.positional().size() != 1) throw UsageError("check expects one scene file (see bsmpm check --help)");
  const int threads = apply_thread_option(args);
  const SceneDescription scene = load_scene(args.positional()[0], args.all("--set"), {render::render_scene_extension()});
  // The prediction and the guards come before seeding, which for a huge scene takes long.
  const RunCost cost = predict_run_cost(scene);
  const bool out = args.has("--out");
  auto warnings = check_run_cost(scene, cost, machine_resources(out ? args.option("--out") : "."), true, !out);
  const WallTimeEstimate wall = estimate_wall_time(scene, cost, threads);
  for (const std::string& w : check_wall_time(scene, wall, false)) warnings.push_back(w);
  print_run_cost(stdout, cost, warnings, wall);
  if (cost.particles > kCheckSeedsUpTo && !args.flag("--build")) {
    std::printf("not built: about %.4g particles, more than the %.0e check seeds (about %.0f s to seed them; "
                "--build does)\n",
                cost.particles, kCheckSeedsUpTo, cost.particles / 0.5e6);
    std::printf("ok: about %.4g particles (predicted)\n", cost.particles);
    return kOk;
  }
  auto sim = build_simulation(scene);
  print_scene_summary(stdout, scene, *sim, threads);
  std::printf("ok: %zu particles\n", sim->particles().size());
  return kOk;
}

}  // namespace bsmpm::cli

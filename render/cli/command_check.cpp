// bsmpm check SCENE [--set KEY=VALUE ...]: validates a scene and prints what a run would do.
#include <cstdio>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/scene_summary.hpp"
#include "core/error.hpp"
#include "scene/run_guards.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "settings/render_options.hpp"

namespace bsmpm::cli {

namespace {
const char* kHelp =
    "usage: bsmpm check SCENE.toml [--set KEY=VALUE ...]\n"
    "\n"
    "Validates the scene (every key, type and range), predicts what a run would cost (particles,\n"
    "steps, memory, output size, and the wall time on this machine from the rates `bsmpm bench`\n"
    "recorded), builds it, and prints the grid, bodies, time step and active effects. Writes\n"
    "nothing. A scene that would not fit in memory (or, with --out DIR, whose\n"
    "output would not fit on that disk), or whose time step is absurdly small, is refused\n"
    "(exit 2) before anything is built.\n"
    "\n"
    "options\n"
    "  --set KEY=VALUE   override a scene value (repeatable)\n"
    "  --out DIR         also check the free space where the run would write\n"
    "  --threads N       OpenMP threads for building, and of the run whose wall time is predicted\n";
}

int command_check(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help"}, {"--threads", "--out"}, {"--set"});
  if (args.flag("--help")) {
    std::fputs(kHelp, stdout);
    return kOk;
  }
  if (args.positional().size() != 1) throw UsageError("check expects one scene file (see bsmpm check --help)");
  const int threads = apply_thread_option(args);
  const SceneDescription scene = load_scene(args.positional()[0], args.all("--set"), {render::render_scene_extension()});
  // The prediction and the guards come before seeding, which for a huge scene takes long.
  const RunCost cost = predict_run_cost(scene);
  const auto warnings = check_run_cost(scene, cost, machine_resources(args.option("--out")), false);
  print_run_cost(stdout, cost, warnings, estimate_wall_time(scene, cost, threads));
  auto sim = build_simulation(scene);
  print_scene_summary(stdout, scene, *sim, threads);
  std::printf("ok: %zu particles\n", sim->particles().size());
  return kOk;
}

}  // namespace bsmpm::cli

// bsmpm check SCENE [--set KEY=VALUE ...]: validates a scene and prints what a run would do.
#include <cstdio>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/scene_summary.hpp"
#include "core/error.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "settings/render_options.hpp"

namespace bsmpm::cli {

namespace {
const char* kHelp =
    "usage: bsmpm check SCENE.toml [--set KEY=VALUE ...]\n"
    "\n"
    "Validates the scene (every key, type and range), builds it, and prints the grid,\n"
    "bodies, time step and active effects. Writes nothing.\n";
}

int command_check(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help"}, {"--threads"}, {"--set"});
  if (args.flag("--help")) {
    std::fputs(kHelp, stdout);
    return kOk;
  }
  if (args.positional().size() != 1) throw UsageError("check expects one scene file (see bsmpm check --help)");
  const int threads = apply_thread_option(args);
  const SceneDescription scene = load_scene(args.positional()[0], args.all("--set"), {render::render_scene_extension()});
  auto sim = build_simulation(scene);
  print_scene_summary(stdout, scene, *sim, threads);
  std::printf("ok: %zu particles\n", sim->particles().size());
  return kOk;
}

}  // namespace bsmpm::cli

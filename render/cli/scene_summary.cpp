#include "cli/scene_summary.hpp"

#include <algorithm>

#include "scene/run_guards.hpp"
#include "step/time_step.hpp"

namespace bsmpm::cli {

void print_scene_summary(std::FILE* out, const SceneDescription& scene, const Simulation& sim, int threads) {
  const GridInfo g = sim.grid_info();
  std::fprintf(out, "scene    %s%s%s\n", scene.path.c_str(), scene.title.empty() ? "" : " - ", scene.title.c_str());
  std::fprintf(out, "grid     %d x %d cells of %.4g x %.4g mm, B-spline order %d, %d x %d control points\n",
               g.cells_x, g.cells_y, g.cell_size.x() * 1e3, g.cell_size.y() * 1e3, g.order, g.cells_x + g.order,
               g.cells_y + g.order);
  for (const Body& b : sim.bodies())
    std::fprintf(out, "body     %-12s %-8s %8zu particles (%.3g x %.3g mm spacing), grid field %d\n", b.name.c_str(),
                 kind_name(b.material), b.size(), b.spacing.x() * 1e3, b.spacing.y() * 1e3, b.layer);
  const double h_min = std::min(g.cell_size.x(), g.cell_size.y());
  if (scene.time.mode == TimeStepSettings::Mode::kFixed)
    std::fprintf(out, "time     0 to %g s, fixed dt = %.3g s; frames every %g s\n", scene.time.end, scene.time.dt,
                 scene.frame_interval);
  else
    std::fprintf(out, "time     0 to %g s, CFL %.2g (first dt = %.3g s, max %.3g s); frames every %g s\n",
                 scene.time.end, scene.time.cfl, time_step(scene.time, sim.max_signal_speed(), h_min),
                 scene.time.max_dt, scene.frame_interval);
  std::fprintf(out, "threads  %d\n", threads);
  std::fprintf(out, "effects\n");
  for (const auto& line : sim.describe_effects()) std::fprintf(out, "  - %s\n", line.c_str());
  std::fflush(out);
}

void print_run_cost(std::FILE* out, const RunCost& cost, const std::vector<std::string>& warnings,
                    const WallTimeEstimate& wall) {
  std::fprintf(out, "cost     about %.4g particles, %.4g steps (dt %.3g s), %.4g particle-steps; memory %s, output %s "
               "(%.0f frames), checkpoint %s\n",
               cost.particles, cost.steps, cost.first_dt, cost.particle_steps, format_bytes(cost.memory_bytes).c_str(),
               format_bytes(cost.output_bytes).c_str(), cost.frames, format_bytes(cost.checkpoint_bytes).c_str());
  std::fprintf(out, "%s\n", wall.line.c_str());
  for (const std::string& w : warnings) std::fprintf(out, "warning  %s\n", w.c_str());
  if (!wall.warning.empty()) std::fprintf(out, "warning  %s\n", wall.warning.c_str());
  std::fflush(out);
}

}  // namespace bsmpm::cli

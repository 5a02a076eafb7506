#include "scene/run_guards.hpp"

#include <sys/statvfs.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"

namespace bsmpm {

namespace {

double meminfo_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return -1.0;
}

// The cgroup v2 limit less what the group uses, if there is a limit.
double cgroup_headroom() {
  std::ifstream max_in("/sys/fs/cgroup/memory.max"), current_in("/sys/fs/cgroup/memory.current");
  std::string max_text;
  double current = 0.0;
  if (!(max_in >> max_text) || max_text == "max" || !(current_in >> current)) return -1.0;
  try {
    return std::stod(max_text) - current;
  } catch (const std::exception&) {
    return -1.0;
  }
}

double free_disk(const std::string& directory) {
  namespace fs = std::filesystem;
  fs::path p = fs::absolute(directory);
  while (!p.empty() && !fs::exists(p) && p != p.parent_path()) p = p.parent_path();
  struct statvfs s {};
  if (statvfs(p.c_str(), &s) != 0) return -1.0;
  return static_cast<double>(s.f_bavail) * static_cast<double>(s.f_frsize);
}

}  // namespace

MachineResources machine_resources(const std::string& directory) {
  MachineResources m;
  m.available_memory_bytes = meminfo_available();
  const double headroom = cgroup_headroom();
  if (headroom >= 0.0 && (m.available_memory_bytes < 0.0 || headroom < m.available_memory_bytes))
    m.available_memory_bytes = headroom;
  if (!directory.empty()) m.free_disk_bytes = free_disk(directory);
  return m;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 5) {
    bytes /= 1024.0;
    ++u;
  }
  return format(u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
}

std::vector<std::string> check_run_cost(const SceneDescription& scene, const RunCost& cost,
                                        const MachineResources& machine, bool checkpoints) {
  if (machine.available_memory_bytes >= 0.0 && cost.memory_bytes > machine.available_memory_bytes)
    throw ResourceError(format(
        "%s: %.4g particles and %d grid field(s) of %.4g control points need about %s of memory; this machine has %s "
        "available. Use a coarser grid (grid.cell_size) or fewer particles per cell",
        scene.path.c_str(), cost.particles, cost.grid_fields, cost.control_points, format_bytes(cost.memory_bytes).c_str(),
        format_bytes(machine.available_memory_bytes).c_str()));
  const std::string why = format("body '%s' carries waves at %.4g m/s (flow %.3g m/s), so dt = %.3g s", cost.stiffest_body.c_str(),
                                 cost.wave_speed, cost.flow_speed, cost.first_dt);
  if (cost.steps > kRefusedSteps)
    throw ResourceError(format("%s: %s: about %.3g time steps to t = %g s (%.3g particle-steps), beyond the %.0e this "
                               "program makes; check the material's stiffness (bulk_modulus, youngs_modulus)",
                               scene.path.c_str(), why.c_str(), cost.steps, scene.time.end, cost.particle_steps,
                               kRefusedSteps));
  // The output after the step count: probe and conservation rows grow with the steps, and
  // an absurd step count is the cause to name.
  const double disk = cost.output_bytes + (checkpoints ? 2.0 * cost.checkpoint_bytes : 0.0);
  if (machine.free_disk_bytes >= 0.0 && disk > machine.free_disk_bytes)
    throw ResourceError(format(
        "%s: %.4g frames of %.4g particles make about %s of output%s; the disk has %s free. Write fewer frames "
        "(output.frame_interval) or use a coarser grid",
        scene.path.c_str(), cost.frames, cost.particles, format_bytes(disk).c_str(),
        checkpoints ? " with checkpoints" : "", format_bytes(machine.free_disk_bytes).c_str()));
  std::vector<std::string> warnings;
  if (cost.steps > kWarnedSteps)
    warnings.push_back(format("%s: about %.3g time steps (%.3g particle-steps): a long run", why.c_str(), cost.steps,
                              cost.particle_steps));
  if (scene.time.mode == TimeStepSettings::Mode::kFixed && scene.time.dt > cost.stable_dt)
    warnings.push_back(format("the fixed step time.dt = %.3g s is %.2g times the acoustic limit %.3g s of body '%s' "
                              "(wave speed %.4g m/s plus flow %.3g m/s): expect the run to become unstable",
                              scene.time.dt, scene.time.dt / cost.stable_dt, cost.stable_dt, cost.stiffest_body.c_str(),
                              cost.wave_speed, cost.flow_speed));
  return warnings;
}

}  // namespace bsmpm

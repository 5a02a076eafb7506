#include "scene/run_guards.hpp"

#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/output_space.hpp"

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

// The process's address-space limit (`ulimit -v`, RLIMIT_AS), -1 when there is none: no
// allocation past it succeeds, whatever the machine has.
double address_space_limit() {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return -1.0;
  return static_cast<double>(limit.rlim_cur);
}

}  // namespace

MachineResources machine_resources(const std::string& directory) {
  MachineResources m;
  m.available_memory_bytes = meminfo_available();
  for (const double limit : {cgroup_headroom(), address_space_limit()})
    if (limit >= 0.0 && (m.available_memory_bytes < 0.0 || limit < m.available_memory_bytes))
      m.available_memory_bytes = limit;
  if (!directory.empty()) {
    m.free_disk_bytes = free_disk_bytes(directory);
    m.file_size_limit_bytes = bsmpm::file_size_limit_bytes();
  }
  return m;
}

std::vector<std::string> check_run_cost(const SceneDescription& scene, const RunCost& cost,
                                        const MachineResources& machine, bool checkpoints, bool disk_full_warns) {
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
  std::vector<std::string> warnings;
  const char* remedy = "Write fewer frames (output.frame_interval) or use a coarser grid; bsmpm run --force starts "
                       "anyway and stops, resumable, when the disk is full";
  auto disk_full = [&](const std::string& what) {
    if (!disk_full_warns) throw ResourceError(scene.path + ": " + what + ". " + remedy);
    warnings.push_back(what + ": the run will stop, resumable, when the disk is full");
  };
  const double disk = cost.output_bytes + (checkpoints ? 2.0 * cost.checkpoint_bytes : 0.0);
  if (machine.free_disk_bytes >= 0.0 && disk > machine.free_disk_bytes)
    disk_full(format("%.4g frames of %.4g particles make about %s of output%s; the disk has %s free", cost.frames,
                     cost.particles, format_bytes(disk).c_str(), checkpoints ? " with checkpoints" : "",
                     format_bytes(machine.free_disk_bytes).c_str()));
  // One file (run.h5 holds nearly all the output; a checkpoint is one file too) may not
  // grow past the process's file-size limit.
  const double largest = std::max(cost.output_bytes, checkpoints ? cost.checkpoint_bytes : 0.0);
  if (largest > machine.file_size_limit_bytes)
    disk_full(format("run.h5 grows to about %s%s, and a file may reach %s (ulimit -f)",
                     format_bytes(cost.output_bytes).c_str(),
                     checkpoints ? (", a checkpoint " + format_bytes(cost.checkpoint_bytes)).c_str() : "",
                     format_bytes(machine.file_size_limit_bytes).c_str()));
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

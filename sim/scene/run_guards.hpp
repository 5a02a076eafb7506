// Guards before a run: a scene whose particles and grid would not fit in memory, whose
// output would not fit on the disk, or whose time step is so small that the run would never
// end, is refused (ResourceError, with the numbers); a step count that is merely large, or a
// fixed step beyond the stable one, is warned about. All from the prediction of run_cost.hpp.
#pragma once

#include <string>
#include <vector>

#include "scene/run_cost.hpp"

namespace bsmpm {

// What this machine offers; a negative value means unknown (then that guard is skipped).
struct MachineResources {
  double available_memory_bytes = -1.0;
  double free_disk_bytes = -1.0;
};

// Memory the kernel can give without swapping (MemAvailable, capped by a cgroup v2 limit), and
// the free space of the file system that holds `directory` (or its nearest existing parent;
// none asked when `directory` is empty).
MachineResources machine_resources(const std::string& directory);

// A predicted step count above this is refused, above the warning limit warned about.
inline constexpr double kRefusedSteps = 1.0e9;
inline constexpr double kWarnedSteps = 1.0e7;

// Throws ResourceError when the run cannot be made; returns the warnings otherwise.
// `checkpoints` adds the space of a checkpoint (two while one replaces the other).
std::vector<std::string> check_run_cost(const SceneDescription& scene, const RunCost& cost,
                                        const MachineResources& machine, bool checkpoints);

// "1.5 GiB", "320 MiB", ...
std::string format_bytes(double bytes);

}  // namespace bsmpm

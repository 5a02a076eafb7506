// Guards before a run: a scene whose particles and grid would not fit in memory, whose
// output would not fit on the disk, or whose time step is so small that the run would never
// end, is refused (ResourceError, with the numbers); a step count that is merely large, or a
// fixed step beyond the stable one, is warned about. All from the prediction of run_cost.hpp.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/format.hpp"  // format_bytes, for the callers
#include "scene/run_cost.hpp"

namespace bsmpm {

// What this machine offers; a negative value means unknown (then that guard is skipped).
struct MachineResources {
  double available_memory_bytes = -1.0;
  double free_disk_bytes = -1.0;
  double file_size_limit_bytes = HUGE_VAL;  // ulimit -f
};

// Memory the kernel can give without swapping (MemAvailable, capped by a cgroup v2 limit and
// by the process's address-space limit, ulimit -v), and
// the free space of the file system that holds `directory` (or its nearest existing parent;
// none asked when `directory` is empty) and the size a file may reach (ulimit -f).
MachineResources machine_resources(const std::string& directory);

// A predicted step count above this is refused, above the warning limit warned about.
inline constexpr double kRefusedSteps = 1.0e9;
inline constexpr double kWarnedSteps = 1.0e7;

// Throws ResourceError when the run cannot be made; returns the warnings otherwise.
// `checkpoints` adds the space of a checkpoint (two while one replaces the other). With
// `disk_full_warns` output that will not fit on the disk is a warning, not a refusal (bsmpm
// run --force: the run stops, resumable, when the disk is full).
std::vector<std::string> check_run_cost(const SceneDescription& scene, const RunCost& cost,
                                        const MachineResources& machine, bool checkpoints,
                                        bool disk_full_warns = false);

}  // namespace bsmpm

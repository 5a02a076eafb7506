// The predicted wall time of a run on this machine, as `bsmpm check` and the start of
// `bsmpm run` print it: the run's particle-steps at the rate of the calibration record that
// fits it best, scaled to the run's features, and its frames (scene/run_calibration.hpp, the
// records read from scene/calibration_file.hpp). Without a record it says how to make one;
// it never fails a command.
#pragma once

#include <string>
#include <vector>

#include "scene/run_cost.hpp"
#include "scene/scene_description.hpp"

namespace bsmpm::cli {

struct WallTimeEstimate {
  double seconds;        // NaN without a calibration
  std::string line;      // "wall     about 3m12s on 2 threads (...)"
  std::string warning;   // an unreadable calibration file, named
};

WallTimeEstimate estimate_wall_time(const SceneDescription& scene, const RunCost& cost, int threads);

// A run predicted to take longer than a month on this machine is a scene far beyond it (a grid
// much finer than meant): refused (ResourceError naming the scene and the time) unless
// `force`, when it is a warning; longer than a day is warned about. Returns the warnings.
inline constexpr double kRefusedWallSeconds = 30.0 * 86400.0;
inline constexpr double kWarnedWallSeconds = 86400.0;
std::vector<std::string> check_wall_time(const SceneDescription& scene, const WallTimeEstimate& wall, bool force);

}  // namespace bsmpm::cli

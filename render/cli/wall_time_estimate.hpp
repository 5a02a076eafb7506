// The predicted wall time of a run on this machine, as `bsmpm check` and the start of
// `bsmpm run` print it: the run's particle-steps at the rate of the calibration record that
// fits it best, scaled to the run's features, and its frames (scene/run_calibration.hpp, the
// records read from scene/calibration_file.hpp). Without a record it says how to make one;
// it never fails a command.
#pragma once

#include <string>

#include "scene/run_cost.hpp"
#include "scene/scene_description.hpp"

namespace bsmpm::cli {

struct WallTimeEstimate {
  double seconds;        // NaN without a calibration
  std::string line;      // "wall     about 3m12s on 2 threads (...)"
  std::string warning;   // an unreadable calibration file, named
};

WallTimeEstimate estimate_wall_time(const SceneDescription& scene, const RunCost& cost, int threads);

}  // namespace bsmpm::cli

#include "cli/wall_time_estimate.hpp"

#include <chrono>
#include <cmath>

#include "cli/progress.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "scene/calibration_file.hpp"
#include "scene/run_calibration.hpp"

namespace bsmpm::cli {

namespace {
std::string duration_text(double s) { return s < 60.0 ? format("%.2g s", s) : format_duration(s); }
}  // namespace

WallTimeEstimate estimate_wall_time(const SceneDescription& scene, const RunCost& cost, int threads) {
  const std::string path = calibration_path();
  const CalibrationFile file = read_calibration(path);
  WallTimeEstimate e{std::nan(""), "", file.warning};
  const RateFeatures features = rate_features(scene, cost);
  const auto choice = choose_calibration(file.records, this_machine(), threads, features);
  if (!choice) {
    e.line = format("wall     no calibration: run `bsmpm bench` once (it records this machine's rate in %s)",
                    path.empty() ? "$BSMPM_CALIBRATION" : path.c_str());
    return e;
  }
  const CalibrationRecord& r = *choice->record;
  const WallTime w = predict_wall_time(cost, features, r);
  e.seconds = w.seconds;
  const double now = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  e.line = format("wall     about %s on %d thread%s: %.3g particle-steps at %.3g M/s and %.0f frames, from the rate "
                  "`bsmpm bench %s` measured (%.3g M/s, %.0f particles, %d thread%s) %s ago",
                  duration_text(e.seconds).c_str(), threads, threads == 1 ? "" : "s", cost.particle_steps,
                  w.particle_steps_per_second * 1e-6, cost.frames, r.scene.c_str(), r.particle_steps_per_second * 1e-6,
                  r.particles, r.threads, r.threads == 1 ? "" : "s", format_age(now - r.recorded_at).c_str());
  if (choice->differences.empty()) {
    e.line += " (same features)";
  } else {
    e.line += "; the nearest record: ";
    for (std::size_t i = 0; i < choice->differences.size(); ++i) e.line += (i ? ", " : "") + choice->differences[i];
  }
  return e;
}

std::vector<std::string> check_wall_time(const SceneDescription& scene, const WallTimeEstimate& wall, bool force) {
  if (!(wall.seconds > kWarnedWallSeconds)) return {};  // also without a calibration (NaN)
  const std::string what = format("the run is predicted to take %s on this machine", format_duration(wall.seconds).c_str());
  if (wall.seconds > kRefusedWallSeconds && !force)
    throw ResourceError(scene.path + ": " + what + ", more than a month. Use a coarser grid (grid.cell_size), or a "
                        "larger machine; bsmpm run --force starts it anyway");
  return {what + (wall.seconds > kRefusedWallSeconds ? ": more than a month" : ": a long run")};
}

}  // namespace bsmpm::cli

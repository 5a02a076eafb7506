// When a run writes DIR/checkpoint.h5: every so much wall-clock time ("10min", "1h"), every
// so much simulated time ("0.05s") or every so many steps ("2000steps"); "0" never. By
// default every 10 minutes of wall time (or what $BSMPM_CHECKPOINT_EVERY says, a site's
// default), so that a run killed without warning (SIGKILL, the out-of-memory killer, a
// reboot) loses at most that much, and a run shorter than that writes none. Simulated-time
// and step checkpoints fall on the first step at or after each multiple, so their places do
// not depend on when a run was resumed; any place gives the same result, bit for bit.
#pragma once

#include <chrono>
#include <cmath>
#include <string>

#include "step/simulation.hpp"

namespace bsmpm::cli {

class CheckpointSchedule {
 public:
  enum class Unit { kNever, kWallSeconds, kSimulatedSeconds, kSteps };

  CheckpointSchedule() = default;  // never
  // "10min", "1.5h", "0.05s", "2000steps" or "0"; throws UsageError naming `source`.
  static CheckpointSchedule parse(const std::string& text, const std::string& source = "--checkpoint-every");
  // --checkpoint-every if given, else $BSMPM_CHECKPOINT_EVERY, else every 10 minutes of wall time.
  static CheckpointSchedule chosen(const std::string* option);

  bool enabled() const { return unit_ != Unit::kNever; }
  Unit unit() const { return unit_; }
  double every() const { return every_; }
  // "every 10 min of wall time", "every 0.05 s of simulated time", "every 2000 steps", "never".
  std::string describe() const;

  // Whether the state after this step is due for a checkpoint (counted as written).
  bool due(const Simulation& sim);
  // Starts counting from the state `sim` is in and from now (a resumed run's checkpoint is
  // not due again).
  void start(const Simulation& sim);

 private:
  double position(const Simulation& sim) const;

  Unit unit_ = Unit::kNever;
  double every_ = 0.0;
  double done_ = 0.0;  // the last slot written (simulated time, steps)
  std::chrono::steady_clock::time_point last_{};  // wall clock
};

// The default: 10 minutes of wall time.
inline constexpr const char* kDefaultCheckpointEvery = "10min";

}  // namespace bsmpm::cli

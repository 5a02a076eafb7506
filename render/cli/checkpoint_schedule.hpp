// --checkpoint-every: every so much simulated time ("0.05s") or every so many steps
// ("2000steps"). Checkpoints fall on the first step at or after each multiple, so their
// places do not depend on when a run was resumed.
#pragma once

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "step/simulation.hpp"

namespace bsmpm::cli {

class CheckpointSchedule {
 public:
  CheckpointSchedule() = default;  // never
  static CheckpointSchedule parse(const std::string& text) {
    CheckpointSchedule s;
    const bool steps = text.size() > 5 && text.compare(text.size() - 5, 5, "steps") == 0;
    const bool seconds = !steps && text.size() > 1 && text.back() == 's';
    if (!steps && !seconds)
      throw UsageError("--checkpoint-every expects simulated seconds (e.g. 0.05s) or steps (e.g. 2000steps), got '" +
                       text + "'");
    const std::string number = text.substr(0, text.size() - (steps ? 5 : 1));
    try {
      std::size_t used = 0;
      s.every_ = std::stod(number, &used);
      if (used != number.size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw UsageError("--checkpoint-every: '" + number + "' is not a number");
    }
    if (!(s.every_ > 0.0) || !std::isfinite(s.every_) || (steps && s.every_ != std::floor(s.every_)))
      throw UsageError("--checkpoint-every expects a positive interval (whole steps), got '" + text + "'");
    s.in_steps_ = steps;
    return s;
  }

  bool enabled() const { return every_ > 0.0; }
  // Whether the state after this step is due for a checkpoint.
  bool due(const Simulation& sim) {
    if (!enabled()) return false;
    const double at = in_steps_ ? static_cast<double>(sim.step_count()) : sim.time() * (1.0 + 1e-12);
    const double slot = std::floor(at / every_);
    if (slot <= done_) return false;
    done_ = slot;
    return true;
  }
  // Starts counting from the state `sim` is in (a resumed run's checkpoint is not due again).
  void start(const Simulation& sim) {
    if (!enabled()) return;
    const double at = in_steps_ ? static_cast<double>(sim.step_count()) : sim.time() * (1.0 + 1e-12);
    done_ = std::floor(at / every_);
  }

 private:
  double every_ = 0.0;
  bool in_steps_ = false;
  double done_ = 0.0;
};

}  // namespace bsmpm::cli

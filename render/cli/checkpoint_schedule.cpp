#include "cli/checkpoint_schedule.hpp"

#include <cstdlib>

#include "core/error.hpp"
#include "core/format.hpp"

namespace bsmpm::cli {

namespace {

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

CheckpointSchedule CheckpointSchedule::parse(const std::string& text, const std::string& source) {
  CheckpointSchedule s;
  if (text == "0") return s;
  struct Suffix {
    const char* text;
    Unit unit;
    double scale;  // to seconds or steps
  };
  // "steps" before "s", "min" before... nothing else ends the same.
  const Suffix suffixes[] = {{"steps", Unit::kSteps, 1.0},
                             {"min", Unit::kWallSeconds, 60.0},
                             {"h", Unit::kWallSeconds, 3600.0},
                             {"s", Unit::kSimulatedSeconds, 1.0}};
  const Suffix* found = nullptr;
  for (const Suffix& suffix : suffixes)
    if (ends_with(text, suffix.text)) {
      found = &suffix;
      break;
    }
  if (!found)
    throw UsageError(source + " expects wall-clock time (10min, 1h), simulated seconds (0.05s), steps (2000steps) "
                     "or 0 (never), got '" + text + "'");
  const std::string number = text.substr(0, text.size() - std::string(found->text).size());
  double value = 0.0;
  try {
    std::size_t used = 0;
    value = std::stod(number, &used);
    if (used != number.size()) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw UsageError(source + ": '" + number + "' is not a number");
  }
  if (!(value > 0.0) || !std::isfinite(value) || (found->unit == Unit::kSteps && value != std::floor(value)))
    throw UsageError(source + " expects a positive interval (whole steps), or 0 for none, got '" + text + "'");
  s.unit_ = found->unit;
  s.every_ = value * found->scale;
  return s;
}

CheckpointSchedule CheckpointSchedule::chosen(const std::string* option) {
  if (option) return parse(*option);
  if (const char* site = std::getenv("BSMPM_CHECKPOINT_EVERY"); site && *site)
    return parse(site, "$BSMPM_CHECKPOINT_EVERY");
  return parse(kDefaultCheckpointEvery);
}

std::string CheckpointSchedule::describe() const {
  switch (unit_) {
    case Unit::kNever: return "never";
    case Unit::kWallSeconds:
      return every_ >= 60.0 ? format("every %g min of wall time", every_ / 60.0)
                            : format("every %g s of wall time", every_);
    case Unit::kSimulatedSeconds: return format("every %g s of simulated time", every_);
    case Unit::kSteps: return format("every %g steps", every_);
  }
  return "never";
}

double CheckpointSchedule::position(const Simulation& sim) const {
  return unit_ == Unit::kSteps ? static_cast<double>(sim.step_count()) : sim.time() * (1.0 + 1e-12);
}

bool CheckpointSchedule::due(const Simulation& sim) {
  if (unit_ == Unit::kNever) return false;
  if (unit_ == Unit::kWallSeconds) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() < every_) return false;
    last_ = now;
    return true;
  }
  const double slot = std::floor(position(sim) / every_);
  if (slot <= done_) return false;
  done_ = slot;
  return true;
}

void CheckpointSchedule::start(const Simulation& sim) {
  last_ = std::chrono::steady_clock::now();
  if (unit_ == Unit::kSimulatedSeconds || unit_ == Unit::kSteps) done_ = std::floor(position(sim) / every_);
}

}  // namespace bsmpm::cli

#include "cli/study_progress.hpp"

#include <algorithm>
#include <fstream>

#include "cli/progress.hpp"
#include "core/format.hpp"
#include "io/run_summary.hpp"

namespace bsmpm::cli {

namespace fs = std::filesystem;

namespace {
// The files of a case directory whose appearance marks its progress.
constexpr const char* kMarkers[] = {"metrics.json", "failed", "started"};
}  // namespace

StudyProgress::StudyProgress(fs::path out_dir, std::vector<std::string> keys, int slots)
    : cases_(std::move(out_dir) / "cases"), keys_(std::move(keys)), slots_(slots),
      start_clock_(std::chrono::steady_clock::now()) {
  for (const auto& key : keys_)
    for (const char* name : kMarkers) {
      std::error_code ec;
      const auto t = fs::last_write_time(cases_ / key / name, ec);
      if (!ec) before_[key + "/" + name] = t;
    }
}

bool StudyProgress::written_since_start(const std::string& key, const char* name) const {
  std::error_code ec;
  const auto t = fs::last_write_time(cases_ / key / name, ec);
  if (ec) return false;
  const auto it = before_.find(key + "/" + name);
  return it == before_.end() || it->second != t;
}

CaseState StudyProgress::state(const std::string& key) const {
  const fs::path dir = cases_ / key;
  if (fs::exists(dir / "metrics.json")) return CaseState::kDone;
  if (written_since_start(key, "failed")) {
    // The marker holds "exit status N"; 130 and 143 are a run stopped by Ctrl-C or SIGTERM
    // (Slurm's scancel, a job's time limit): it resumes.
    std::ifstream marker(dir / "failed");
    std::string word1, word2;
    int status = 0;
    marker >> word1 >> word2 >> status;
    return status == 130 || status == 143 ? CaseState::kInterrupted : CaseState::kFailed;
  }
  if (written_since_start(key, "started")) return CaseState::kRunning;
  return CaseState::kWaiting;
}

std::optional<double> StudyProgress::wall_seconds(const std::string& key) {
  const auto it = wall_.find(key);
  if (it != wall_.end()) return it->second;
  double wall = 0.0;
  try {
    wall = read_run_summary((cases_ / key).string()).wall_seconds;
  } catch (const std::exception&) {
    // A summary still being renamed into place: read it next time.
    return std::nullopt;
  }
  wall_[key] = wall;
  return wall;
}

StudyStatus StudyProgress::poll() {
  StudyStatus s;
  double wall_sum = 0.0;
  int wall_count = 0;
  std::vector<double> running_elapsed;
  const auto now = fs::file_time_type::clock::now();
  for (const auto& key : keys_) {
    switch (state(key)) {
      case CaseState::kDone: {
        ++s.done;
        if (!written_since_start(key, "metrics.json")) ++s.reused;
        if (const auto w = wall_seconds(key)) wall_sum += *w, ++wall_count;
        break;
      }
      case CaseState::kFailed:
        ++s.failed;
        s.failed_keys.push_back(key);
        break;
      case CaseState::kRunning: {
        ++s.running;
        std::error_code ec;
        const auto started = fs::last_write_time(cases_ / key / "started", ec);
        running_elapsed.push_back(ec ? 0.0 : std::chrono::duration<double>(now - started).count());
        break;
      }
      case CaseState::kInterrupted: ++s.interrupted; break;
      default: ++s.waiting;
    }
  }
  if (wall_count > 0) {
    // Work left in case-seconds, shared among the slots that run side by side.
    const double mean = wall_sum / wall_count;
    double left = s.waiting * mean;
    for (double e : running_elapsed) left += std::max(0.0, mean - e);
    const int slots = slots_ > 0 ? slots_ : std::max(1, s.running);
    s.eta_seconds = left / std::min(slots, std::max(1, s.running + s.waiting));
  }
  return s;
}

std::string StudyProgress::line(const StudyStatus& s) const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock_).count();
  const std::string reused = s.reused ? " (" + std::to_string(s.reused) + " reused)" : "";
  return format("%d/%zu done%s, %d running, %d failed, %d waiting  elapsed %s  ETA %s", s.done, keys_.size(),
                reused.c_str(), s.running, s.failed, s.waiting, format_duration(elapsed).c_str(),
                s.eta_seconds ? format_duration(*s.eta_seconds).c_str() : "--");
}

}  // namespace bsmpm::cli

// The state of a running study as its case directories show it (docs/studies.md,
// "Progress"): done (metrics.json), failed (a `failed` marker written by this invocation;
// interrupted if it says exit status 130 or 143), running (a `started` marker written by it),
// waiting; and an ETA from the mean wall time of the finished cases. "Written by this
// invocation" means absent or different when the object was made: the markers' times are
// snapshotted then, so no clock resolution or second-long slack decides what was reused.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bsmpm::cli {

enum class CaseState { kWaiting, kRunning, kDone, kFailed, kInterrupted };

struct StudyStatus {
  int done = 0, reused = 0, running = 0, failed = 0, waiting = 0, interrupted = 0;
  std::optional<double> eta_seconds;  // unknown until a case has finished
  std::vector<std::string> failed_keys;
};

class StudyProgress {
 public:
  // `slots`: how many cases run side by side at most (0: as many as are running).
  StudyProgress(std::filesystem::path out_dir, std::vector<std::string> keys, int slots);

  CaseState state(const std::string& key) const;
  StudyStatus poll();
  std::string line(const StudyStatus& s) const;  // one line of progress

 private:
  // True if `key`'s marker `name` exists and was not there, with this time, at construction.
  bool written_since_start(const std::string& key, const char* name) const;
  std::optional<double> wall_seconds(const std::string& key);  // from the case's summary.json, cached

  std::filesystem::path cases_;
  std::vector<std::string> keys_;
  int slots_;
  std::map<std::string, std::filesystem::file_time_type> before_;  // "key/marker" -> time at construction
  std::chrono::steady_clock::time_point start_clock_;
  std::map<std::string, double> wall_;
};

}  // namespace bsmpm::cli

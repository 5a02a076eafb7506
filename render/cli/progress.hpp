// Progress of long commands on stderr: "render  12/106  t = 0.11 s  8.3 /s  ETA 11s",
// rewritten in place on a terminal, one line every 10 s otherwise; nothing with --quiet.
#pragma once

#include <chrono>
#include <string>

namespace bsmpm::cli {

class Progress {
 public:
  Progress(std::string what, long total, bool quiet);
  // After item `done` (1-based) of the total; `detail` describes it.
  void update(long done, const std::string& detail);
  // Ends the in-place line.
  void finish();

 private:
  std::string what_;
  long total_;
  bool quiet_, tty_;
  std::chrono::steady_clock::time_point start_;
  double last_line_ = -1e9;
  bool open_line_ = false;
};

std::string format_duration(double seconds);

}  // namespace bsmpm::cli

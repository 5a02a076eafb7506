#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "core/format.hpp"

namespace bsmpm::cli {

std::string format_duration(double s) {
  if (s >= 3600) return format("%dh%02dm", int(s / 3600), int(s / 60) % 60);
  if (s >= 60) return format("%dm%02ds", int(s / 60), int(s) % 60);
  return format("%.0fs", s);
}

Progress::Progress(std::string what, long total, bool quiet)
    : what_(std::move(what)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()) {}

void Progress::update(long done, const std::string& detail) {
  if (quiet_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (!tty_ && elapsed - last_line_ < 10.0 && done < total_) return;
  last_line_ = elapsed;
  const double rate = done / std::max(elapsed, 1e-9);
  const double eta = (total_ - done) / std::max(rate, 1e-9);
  std::fprintf(stderr, "%s%s %ld/%ld  %s  %.1f /s  ETA %s%s", tty_ ? "\r" : "", what_.c_str(), done, total_,
               detail.c_str(), rate, format_duration(eta).c_str(), tty_ ? "   " : "\n");
  std::fflush(stderr);
  open_line_ = tty_;
}

void Progress::finish() {
  if (open_line_) std::fputc('\n', stderr);
  open_line_ = false;
}

}  // namespace bsmpm::cli

#include "cli/interruption.hpp"

#include <atomic>
#include <csignal>

namespace bsmpm::cli {

namespace {
std::atomic<bool> g_interrupted{false};

extern "C" void on_interruption(int sig) {
  g_interrupted.store(true);
  std::signal(sig, SIG_DFL);
}
}  // namespace

void catch_interruptions() {
  std::signal(SIGINT, on_interruption);
  std::signal(SIGTERM, on_interruption);
}

bool interrupted() { return g_interrupted.load(); }

}  // namespace bsmpm::cli

#include "cli/interruption.hpp"

#include <atomic>
#include <csignal>

namespace bsmpm::cli {

namespace {
std::atomic<int> g_signal{0};

extern "C" void on_interruption(int sig) {
  g_signal.store(sig);
  std::signal(sig, SIG_DFL);
}
}  // namespace

void catch_interruptions() {
  std::signal(SIGINT, on_interruption);
  std::signal(SIGTERM, on_interruption);
}

bool interrupted() { return g_signal.load() != 0; }

int interrupted_exit_status() { return 128 + (g_signal.load() != 0 ? g_signal.load() : SIGINT); }

}  // namespace bsmpm::cli

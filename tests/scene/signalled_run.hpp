// The program run as a child that the test signals once a condition on its output holds:
// the interrupted and killed runs of run_output_test and resume_test.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

namespace bsmpm::test {

// Runs BSMPM_EXECUTABLE with `args` (its output to /dev/null), and `environment`
// ("NAME=VALUE") added to its environment, and returns its wait status.
// With a `signal`, sends it once `ready()` holds: the child is stopped first (SIGSTOP), so
// that it makes no progress between the test seeing the condition and the signal, then
// signalled and let go on (SIGCONT). There is no deadline: the wait ends when the condition
// holds or the child ends (ctest's timeout is the backstop); a child that ended before the
// condition held returns its status, which the caller's checks then refuse. Give the run
// enough work after the condition that it cannot end within one poll (5 ms).
inline int run_signalled(const std::vector<std::string>& args, int signal = 0,
                         const std::function<bool()>& ready = [] { return false; },
                         const std::string& environment = "") {
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(126);
    if (!environment.empty() && putenv(const_cast<char*>(environment.c_str())) != 0) _exit(125);
    std::vector<char*> argv{const_cast<char*>(BSMPM_EXECUTABLE)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(BSMPM_EXECUTABLE, argv.data());
    _exit(127);
  }
  int status = 0;
  while (signal != 0) {
    if (waitpid(pid, &status, WNOHANG) == pid) return status;  // ended before the condition
    if (ready()) {
      kill(pid, SIGSTOP);
      if (waitpid(pid, &status, WUNTRACED) == pid && !WIFSTOPPED(status)) return status;  // ended meanwhile
      kill(pid, signal);
      kill(pid, SIGCONT);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  while (waitpid(pid, &status, 0) == pid && WIFSTOPPED(status)) {
  }
  return status;
}

}  // namespace bsmpm::test

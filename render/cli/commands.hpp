// The sub-commands of the bsmpm program. Each returns the process exit code.
#pragma once

#include <string>
#include <vector>

namespace bsmpm::cli {

// Exit codes shared by all commands (the table: bsmpm --help, README.md). A command stopped
// by a signal exits 128 + its number (cli/interruption.hpp).
enum ExitCode { kOk = 0, kFailure = 1, kBadInput = 2, kUnstable = 3, kOutOfSpace = 4, kInterrupted = 130 };

int command_run(const std::vector<std::string>& args);
int command_check(const std::vector<std::string>& args);
int command_bench(const std::vector<std::string>& args);
int command_render(const std::vector<std::string>& args);
int command_movie(const std::vector<std::string>& args);
int command_compare(const std::vector<std::string>& args);
int command_study(const std::vector<std::string>& args);
int command_metrics(const std::vector<std::string>& args);

}  // namespace bsmpm::cli

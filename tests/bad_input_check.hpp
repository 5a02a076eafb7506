// A check shared by the command-line tests: the program stopped on bad input (a usage or
// input error, exit status 2) and said why. Kept apart from test_support.hpp, which programs
// other than Catch tests include.
#pragma once

#include <string>

#include <catch2/catch.hpp>

#include "test_support.hpp"

namespace bsmpm::test {

// Runs `run(args)` (a ProgramResult) and checks exit status 2 and `message` in its output.
// Returns the output for the caller's further checks.
template <class Run>
std::string check_bad_input(Run&& run, const std::string& args, const std::string& message) {
  INFO("bsmpm " << args);
  const ProgramResult r = run(args);
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(contains(r.output, message));
  return r.output;
}

}  // namespace bsmpm::test

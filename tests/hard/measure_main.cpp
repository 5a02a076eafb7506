// Prints the hard-case measures of one scene (for choosing the tolerances and the time steps):
// hard_case_measure NAME [KEY=VALUE ...]
#include <cstdio>

#include "hard_case.hpp"

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  std::vector<std::string> overrides(argv + 2, argv + argc);
  const auto r = bsmpm::test::run_hard_case(argv[1], overrides);
  std::printf("%s\n", bsmpm::test::describe(r).c_str());
  return r.finished ? 0 : 1;
}

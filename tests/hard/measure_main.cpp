// Prints the hard-case measures of one scene (for choosing the tolerances and the time steps):
// hard_case_measure NAME [KEY=VALUE ...]
#include <cstdio>
#include <cstdlib>

#include "hard_case.hpp"

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  std::vector<std::string> overrides(argv + 2, argv + argc);
  double factor = 0.0;  // FIXED_DT_FACTOR=k: a fixed step k times the acoustic limit
  if (const char* f = std::getenv("FIXED_DT_FACTOR")) factor = std::atof(f);
  const auto r = bsmpm::test::run_hard_case(argv[1], overrides, factor);
  std::printf("%s\n", bsmpm::test::describe(r).c_str());
  return r.finished ? 0 : 1;
}

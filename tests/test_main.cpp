#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include <string>

// Linked into every suite. ctest runs each test case by passing its name to Catch2 as a
// filter, and catch_discover_tests splits a name at ';' into two filters that match no test
// case: such a test passes without running a single assertion.
TEST_CASE("No test name holds a semicolon, which would make ctest run nothing under that name", "[meta]") {
  int names = 0;
  for (const auto& test : Catch::getRegistryHub().getTestCaseRegistry().getAllTests()) {
    INFO(test.name);
    CHECK(test.name.find(';') == std::string::npos);
    ++names;
  }
  CHECK(names > 1);
}

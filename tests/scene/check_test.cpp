// bsmpm check answers from the scene's description, before seeding: every shipped scene at a
// grid fine enough for about 5 million particles is either refused with the numbers (memory,
// disk, time) or predicted without a particle seeded, so check answers at once whatever the grid (the
// elastic gate at 0.1 mm took 34 s to seed 17 million particles before it said anything).
// It runs under an address-space limit far below what seeding those particles needs: a check
// that seeded them would fail for lack of memory instead.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

using test::contains;

// The shipped scene's grid and particles, from `bsmpm check`'s own lines: "grid     N x M cells
// of A x B mm" and "ok: N particles".
double number_after(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + marker.size()));
}

}  // namespace

TEST_CASE("check answers every shipped scene from its description, seeding none of a fine grid", "[cli][guards]") {
  const fs::path dir = test::scratch_dir("check_fine");
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(test::source_path("scenes"))) {
    if (entry.path().extension() != ".toml") continue;
    ++scenes;
    const std::string scene = entry.path().string();
    INFO(scene);
    const auto shipped = test::run_program("check " + scene + " --threads 1", dir / "shipped.log");
    INFO(shipped.output);
    REQUIRE(shipped.status == 0);
    CHECK(contains(shipped.output, "ok: "));
    // A grid with about 5 million particles: seeding them needs more than the 2 GiB of
    // address space the check runs in (the program and its libraries take about 0.9 GiB).
    const double particles = number_after(shipped.output, "ok: ");
    const double fine = number_after(shipped.output, " cells of ") * 1e-3 / std::ceil(std::sqrt(5e6 / particles));
    const auto r = test::run_program("check " + scene + " --threads 1 --set grid.cell_size=" + std::to_string(fine),
                                     dir / "fine.log", "prlimit --as=2147483648 --");
    INFO(r.output);
    if (r.status == 2) {  // refused, with its numbers
      CHECK((contains(r.output, "of memory; this machine has") || contains(r.output, "time steps to t =") ||
             contains(r.output, "more than a month")));
      continue;
    }
    CHECK(r.status == 0);
    CHECK(contains(r.output, "cost     about "));
    CHECK(contains(r.output, "not built: about "));
    CHECK(contains(r.output, "(predicted)"));
  }
  CHECK(scenes == 15);  // scenes/*.toml: the paper's, the tests', and four incompressible twins
}

// Collapse of a water column of width a and height 2a against Martin & Moyce (1952),
// Table 2 (tests/data/martin_moyce_1952/front_n2_2.txt): surge front Z = x/a against
// T = t sqrt(2g/a), for T <= 2.5.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

struct Row {
  double T, Z;
};

std::vector<Row> martin_moyce_table() {
  std::ifstream in(test::source_path("tests/data/martin_moyce_1952/front_n2_2.txt"));
  REQUIRE(in.good());
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    Row r;
    s >> r.T >> r.Z;
    rows.push_back(r);
  }
  return rows;
}

// Linear interpolation of the front probe (columns t, T*, front) at T.
double front_at(const Probe& probe, double T) {
  for (std::size_t r = 1; r < probe.row_count(); ++r) {
    const double* a = probe.row(r - 1);
    const double* b = probe.row(r);
    if (b[1] >= T) return a[2] + (b[2] - a[2]) * (T - a[1]) / (b[1] - a[1]);
  }
  FAIL("the run ended before T = " << T);
  return 0.0;
}

}  // namespace

TEST_CASE("Martin & Moyce surge front within 10 % for T <= 2.5", "[physics][martin_moyce]") {
  // scenes/martin_moyce.toml: a / 16 grid, order 2, 2 x 2 particles per cell, 5 % PIC
  // blending (solver.flip = 0.95). The reference scale of the scene makes T* = T.
  const auto run = test::run_scene("martin_moyce.toml");
  const Probe* front = test::find_probe(*run.sim, "front");
  REQUIRE(front != nullptr);
  const double a = 0.05715;
  int compared = 0;
  for (const Row& r : martin_moyce_table()) {
    if (r.T > 2.5) break;
    const double Z = front_at(*front, r.T) / a;
    INFO("T = " << r.T << ": Z = " << Z << " against " << r.Z);
    // 10 %: the bound; the experiment's own scatter and its delayed release make the
    // measured front lag inviscid models (see docs/validation.md).
    CHECK(Z == Approx(r.Z).epsilon(0.10));
    ++compared;
  }
  CHECK(compared == 9);  // T = 0.41 ... 2.32
}

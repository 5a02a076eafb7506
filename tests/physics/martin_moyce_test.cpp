// Collapse of a water column of width a and height 2a against Martin & Moyce (1952),
// Table 2 (tests/data/martin_moyce_1952/front_n2_2.txt): surge front Z = x/a against
// T = t sqrt(2g/a), for T <= 2.5. Two variants of the velocity update, each pinned here
// (the scene's own settings may change): the scene's 5 % PIC blend, and the paper's pure
// FLIP; and the blend's grid convergence, a/16 against a/32.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Measured and bounds, in one place (they depend on the fluid solver: re-measure after a
// change to it). Signed relative error of the front, (Z - Z_table) / Z_table, over the nine
// table rows T = 0.41 ... 2.32; order 2, 2 x 2 particles per cell, measured on 2026-12-01.
// The margins are the probe's own resolution: the front is the foremost particle plus half
// a spacing, so it moves in steps of up to one spacing, a/32 = 0.031 in Z at a/16 (1-3 % of
// Z), a/64 at a/32; 2 points each way at a/16, 1.5 at a/32.
struct Band {
  double lowest, highest;
};
// 5 % PIC at a/16: measured -3.4 % (T = 0.41) ... +6.3 % (T = 1.19).
constexpr Band kBlendBand{-0.055, 0.085};
// Pure FLIP at a/16: measured -1.4 % (T = 0.41) ... +20.9 % (T = 1.19), the one-particle
// tongue running ahead (docs/validation.md). Its lead is part of the claim: it must stay
// above 18 % (measured 20.9 % less one probe step), or the variant changed.
constexpr Band kFlipBand{-0.035, 0.23};
constexpr double kFlipLeadAtLeast = 0.18;
// 5 % PIC at a/32: measured -2.4 % (T = 0.41) ... +11.0 % (T = 1.19): less numerical
// dissipation, the front runs ahead as with pure FLIP (docs/validation.md).
constexpr Band kBlendFineBand{-0.04, 0.125};
// 5 % PIC, a/16 against a/32: measured largest |Z16 - Z32| / Z32 = 5.4 % (T = 2.32),
// growing from 1.0 % at T = 0.41; bound 7 %.
constexpr double kGridChangeBound = 0.07;

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
    if (r.T <= 2.5) rows.push_back(r);
  }
  REQUIRE(rows.size() == 9);  // T = 0.41 ... 2.32
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

const double kA = 0.05715;  // the column's width a [m]

// Z = x_front / a at the table's T, for the scene with the grid a / cells_per_a and the
// given FLIP share; the other solver settings pinned as the scene ships them.
std::vector<double> fronts(int cells_per_a, double flip) {
  const auto run = test::run_scene("martin_moyce.toml", {"grid.cell_size=" + std::to_string(kA / cells_per_a),
                                                         "grid.order=2", "grid.particles_per_cell=2",
                                                         "solver.flip=" + std::to_string(flip),
                                                         "solver.smooth_fluid_volume=true"});
  const Probe* front = test::find_probe(*run.sim, "front");
  REQUIRE(front != nullptr);
  std::vector<double> Z;
  for (const Row& r : martin_moyce_table()) Z.push_back(front_at(*front, r.T) / kA);
  return Z;
}

// Checks every row's relative error against `band`; returns the largest error.
double check_band(const std::vector<double>& Z, const Band& band) {
  const auto table = martin_moyce_table();
  double largest = -1.0;
  for (std::size_t k = 0; k < table.size(); ++k) {
    const double error = (Z[k] - table[k].Z) / table[k].Z;
    INFO("T = " << table[k].T << ": Z = " << Z[k] << " against " << table[k].Z << " (" << 100 * error << " %)");
    CHECK(error >= band.lowest);
    CHECK(error <= band.highest);
    largest = std::max(largest, error);
  }
  return largest;
}

}  // namespace

TEST_CASE("Martin & Moyce surge front with 5 % PIC at a/16 within its measured band", "[physics][martin_moyce]") {
  check_band(fronts(16, 0.95), kBlendBand);
}

TEST_CASE("Martin & Moyce surge front with pure FLIP at a/16 within its measured band", "[physics][martin_moyce]") {
  const double lead = check_band(fronts(16, 1.0), kFlipBand);
  CHECK(lead > kFlipLeadAtLeast);
}

TEST_CASE("Martin & Moyce surge front with 5 % PIC: a/16 against a/32", "[physics][martin_moyce][convergence]") {
  const auto coarse = fronts(16, 0.95), fine = fronts(32, 0.95);
  const auto table = martin_moyce_table();
  for (std::size_t k = 0; k < table.size(); ++k) {
    const double change = std::abs(coarse[k] - fine[k]) / fine[k];
    INFO("T = " << table[k].T << ": Z = " << coarse[k] << " at a/16, " << fine[k] << " at a/32: change "
                << 100 * change << " %");
    CHECK(change <= kGridChangeBound);
  }
  check_band(fine, kBlendFineBand);
}

namespace {

// The incompressible twin (scenes/martin_moyce_incompressible.toml, method.md §12) at a/16,
// with the velocity update and step given.
std::vector<double> fronts_incompressible(const std::vector<std::string>& overrides) {
  std::vector<std::string> all = {"grid.cell_size=" + std::to_string(kA / 16), "grid.order=2",
                                  "grid.particles_per_cell=2"};
  all.insert(all.end(), overrides.begin(), overrides.end());
  const auto run = test::run_scene("martin_moyce_incompressible.toml", all);
  const Probe* front = test::find_probe(*run.sim, "front");
  REQUIRE(front != nullptr);
  std::vector<double> Z;
  for (const Row& r : martin_moyce_table()) Z.push_back(front_at(*front, r.T) / kA);
  return Z;
}

}  // namespace

// The incompressible model in the weakly compressible model's bands, variant by variant
// (measured 2026-12-03). A PIC share per step damps per step: at the incompressible model's
// own steps (0.8-1 ms, the flow's; the weakly compressible model takes 30 us) 5 % PIC damps
// some 30 times less per second, so the 5 % PIC variant is run at the weakly compressible
// model's step, and at its own step the model is compared in pure FLIP's band.
TEST_CASE("Martin & Moyce, incompressible, pure FLIP at its own step: in pure FLIP's band",
          "[physics][martin_moyce][incompressible]") {
  // Measured -1.1 % (T = 0.41) ... +21.4 % (T = 1.19): the one-particle tongue, as pure FLIP's
  // in the weakly compressible model (-1.4 ... +20.9 %).
  const double lead = check_band(fronts_incompressible({"solver.velocity_update=\"flip\"", "solver.flip=1.0"}), kFlipBand);
  CHECK(lead > kFlipLeadAtLeast);
}

TEST_CASE("Martin & Moyce, incompressible, 5 % PIC at the weakly compressible step: in its band",
          "[physics][martin_moyce][incompressible]") {
  // Measured -3.7 % (T = 0.41) ... +5.3 % (T = 1.19) against the weakly compressible
  // model's -3.4 ... +6.3 % (30 us steps both).
  check_band(fronts_incompressible({"solver.velocity_update=\"flip\"", "solver.flip=0.95", "time.max_dt=3e-5"}),
             kBlendBand);
}

TEST_CASE("Martin & Moyce, incompressible as shipped (APIC, its own step): in pure FLIP's band",
          "[physics][martin_moyce][incompressible]") {
  // Measured -1.0 % (T = 0.41) ... +20.1 % (T = 1.19): APIC keeps the tongue as FLIP does.
  check_band(fronts_incompressible({}), kFlipBand);
}

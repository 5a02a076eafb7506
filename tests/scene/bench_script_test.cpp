// scripts/bench --compare: the change per phase and in total between two records of
// `bsmpm bench --json`, given as two files or as one file and a fresh run of the same case.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

const fs::path& scratch() { return test::scratch_root("bench_script"); }

test::ProgramResult bench_script(const std::string& args) {
  const fs::path log = scratch() / "bench.log";
  return test::run_shell("BSMPM_EXECUTABLE='" + std::string(BSMPM_EXECUTABLE) + "' " +
                             test::source_path("scripts/bench") + " " + args,
                         log);
}

// The line of `text` that starts with `label` followed by a space, its words joined by one
// space (the columns' widths are not the test's business).
std::string line_of(const std::string& text, const std::string& label) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(label + " ", 0) == 0) {
      std::istringstream words(line);
      std::string joined;
      for (std::string w; words >> w;) joined += (joined.empty() ? "" : " ") + w;
      return joined;
    }
  return "";
}

std::string record(double weights, double p2g, double total, double rate, int threads) {
  std::ostringstream s;
  s << "{\"scene\": \"scenes/x.toml\", \"overrides\": [], \"particles\": 1000, \"threads\": " << threads
    << ", \"steps\": 10, \"cell_size\": [0.005, 0.005], \"seconds_per_step\": " << total
    << ", \"particle_steps_per_second\": " << rate
    << ", \"bytes_per_particle\": 300, \"bytes_per_control_point\": 100, "
       "\"phase_seconds_per_step\": {\"weights\": "
    << weights << ", \"particle_to_grid\": " << p2g << "}}\n";
  return s.str();
}

}  // namespace

TEST_CASE("scripts/bench --compare shows the change per phase and in total", "[cli][bench]") {
  const fs::path old_json = scratch() / "old.json", new_json = scratch() / "new.json";
  std::ofstream(old_json) << record(0.002, 0.004, 0.010, 1e5, 2);
  std::ofstream(new_json) << record(0.001, 0.005, 0.008, 1.25e5, 2);
  const auto r = bench_script("--compare " + old_json.string() + " " + new_json.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  // phase, old ms per step, new ms per step, change
  CHECK(line_of(r.output, "weights") == "weights 2.000 1.000 -50.0 %");
  CHECK(line_of(r.output, "particle_to_grid") == "particle_to_grid 4.000 5.000 +25.0 %");
  CHECK(line_of(r.output, "total") == "total 10.000 8.000 -20.0 %");
  CHECK(line_of(r.output, "particle-steps/s") == "particle-steps/s 1e+05 1.25e+05 +25.0 %");
  CHECK(line_of(r.output, "bytes/particle") == "bytes/particle 300.0 300.0 +0.0 %");
  CHECK(r.output.find("differ") == std::string::npos);
  // Records of different thread counts are compared, with a note.
  std::ofstream(new_json) << record(0.001, 0.005, 0.008, 1.25e5, 1);
  CHECK(bench_script("--compare " + old_json.string() + " " + new_json.string()).output.find("differ in") !=
        std::string::npos);
}

TEST_CASE("scripts/bench --compare OLD.json runs OLD's case again", "[cli][bench]") {
  const fs::path old_json = scratch() / "hydrostatic.json";
  const std::string scene = test::scene_path("hydrostatic_tank.toml");
  const auto made =
      test::run_program("bench " + scene + " --steps 2 --warmup 0 --threads 1 --set time.end=1 --json", scratch() / "made.log");
  REQUIRE(made.status == 0);
  std::ofstream(old_json) << made.output;
  const auto r = bench_script("--compare " + old_json.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("new: " + scene + ", 6400 particles, 1 threads, 2 steps") != std::string::npos);
  CHECK(r.output.find("differ") == std::string::npos);
  CHECK(!line_of(r.output, "particle_to_grid").empty());
  CHECK(!line_of(r.output, "total").empty());
}

TEST_CASE("scripts/bench --smoothing-cost adds the smoothing's share of the step, from a run without it",
          "[cli][bench]") {
  // The share is a timing, the machine's business; what the script owes is the second run
  // (the same case with the particles' own volume) and the share of the two records it kept.
  const fs::path saved = scratch() / "smoothing_records";
  fs::remove_all(saved);
  const auto r = bench_script("--no-reference --threads 1 --steps 2 --save " + saved.string() + " --smoothing-cost " +
                              test::scene_path("lobovsky_h300.toml") + "@0.02");
  INFO(r.output);
  REQUIRE(r.status == 0);
  std::istringstream lines(r.output);
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  CHECK(header.substr(header.find_last_not_of(' ') - 10, 11) == "smoothing_%");
  // scene, cell_mm, threads, particles, ms_per_step, particle_st/s, smoothing_%
  std::istringstream words(row);
  std::string scene;
  double cell = 0, threads = 0, particles = 0, ms = 0, rate = 0, share = std::nan("");
  words >> scene >> cell >> threads >> particles >> ms >> rate >> share;
  CHECK(scene == "lobovsky_h300");
  // DIR/SCENE@CELL_t1.json and DIR/SCENE@CELL_t1_particle_volume.json (CELL: the actual size).
  std::string with, without;
  int records = 0;
  for (const auto& entry : fs::directory_iterator(saved)) {
    const std::string name = entry.path().filename().string();
    ++records;
    (name.find("_t1_particle_volume.json") != std::string::npos ? without : with) = test::read_text(entry.path());
  }
  CHECK(records == 2);
  INFO(with << "\n" << without);
  CHECK(without.find("solver.fluid_volume=\\\"particle\\\"") != std::string::npos);
  CHECK(with.find("fluid_volume") == std::string::npos);
  auto per_step = [](const std::string& json) {
    const auto at = json.find("\"seconds_per_step\": ");
    REQUIRE(at != std::string::npos);
    return std::stod(json.substr(at + 20));
  };
  // The printed share (one decimal) is 100 (t_with - t_without) / t_with.
  CHECK(share == Approx(100.0 * (per_step(with) - per_step(without)) / per_step(with)).margin(0.05));
}

TEST_CASE("scripts/bench --instructions counts the step's instructions under callgrind, away from the calibration",
          "[cli][bench]") {
  // The count is the build's business; what the script owes is a count per particle-step of
  // the steps after the warm-up (a 6-step bench less a 2-step one, over 4 x the particles),
  // and no calibration record from the runs under valgrind, which are some 50 times slower
  // and would mislead every wall-time prediction after them.
  const fs::path calibration = scratch() / "instructions_calibration.json";
  fs::remove(calibration);
  const auto r = test::run_shell("BSMPM_CALIBRATION='" + calibration.string() + "' BSMPM_EXECUTABLE='" +
                                     std::string(BSMPM_EXECUTABLE) + "' " + test::source_path("scripts/bench") +
                                     " --no-reference --threads 1 --steps 2 --instructions " +
                                     test::scene_path("lobovsky_h300.toml") + "@0.02",
                                 scratch() / "instructions.log");
  INFO(r.output);
  REQUIRE(r.status == 0);
  const std::string label = "instructions per particle-step (1 thread, callgrind): ";
  const auto at = r.output.find(label);
  REQUIRE(at != std::string::npos);
  const double count = std::stod(r.output.substr(at + label.size()));
  // A MUSL step of quadratic B-splines touches 9 control points a particle in four transfers:
  // hundreds of instructions at the least; the shipped scene measured 2,407 at 10 mm.
  CHECK(count > 500);
  CHECK(count < 20000);
  // The timed run (--steps 2 above) records its rate as a bench does, and the counted ones,
  // of the same scene and thread count, do not replace it: the record holds the printed rate.
  std::istringstream lines(r.output);
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  std::istringstream words(row);
  std::string scene;
  double cell = 0, threads = 0, particles = 0, ms = 0, rate = 0;
  words >> scene >> cell >> threads >> particles >> ms >> rate;
  const std::string recorded = test::read_text(calibration);
  const std::string key = "\"particle_steps_per_second\": ";
  const auto rate_at = recorded.find(key);
  REQUIRE(rate_at != std::string::npos);
  CHECK(std::stod(recorded.substr(rate_at + key.size())) == Approx(rate).epsilon(0.006));  // printed to 3 digits
}

// The calibration file (scene/calibration_file.hpp): where it lives, `bsmpm bench` adding its
// rate to it, `bsmpm check` and `bsmpm run` predicting the wall time from it, and a file that
// cannot be read being a warning that names it, never a failure. Rates are the machine's:
// nothing here asserts a time.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <vector>

#include "io/run_summary.hpp"
#include "scene/calibration_file.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

using test::contains;

// The program with BSMPM_CALIBRATION set to `calibration`.
test::ProgramResult bsmpm_calibrated(const fs::path& calibration, const std::string& args) {
  return test::run_program(args, calibration.parent_path().parent_path() / "program.log",
                           "env BSMPM_CALIBRATION='" + calibration.string() + "'");
}

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The line of the output that starts with `start`, or "".
std::string line_starting(const std::string& output, const std::string& start) {
  for (std::size_t at = 0; at < output.size();) {
    const std::size_t end = std::min(output.find('\n', at), output.size());
    if (output.compare(at, start.size(), start) == 0) return output.substr(at, end - at);
    at = end + 1;
  }
  return "";
}

const std::string kScene = test::scene_path("hydrostatic_tank.toml");

}  // namespace

TEST_CASE("The calibration lives in BSMPM_CALIBRATION, else the XDG cache, else ~/.cache", "[calibration]") {
  struct Restore {
    std::string names[3] = {"BSMPM_CALIBRATION", "XDG_CACHE_HOME", "HOME"};
    std::string values[3];
    bool set[3] = {};
    Restore() {
      for (int i = 0; i < 3; ++i)
        if (const char* v = std::getenv(names[i].c_str())) values[i] = v, set[i] = true;
    }
    ~Restore() {
      for (int i = 0; i < 3; ++i)
        set[i] ? setenv(names[i].c_str(), values[i].c_str(), 1) : unsetenv(names[i].c_str());
    }
  } restore;
  setenv("BSMPM_CALIBRATION", "/x/mine.json", 1);
  setenv("XDG_CACHE_HOME", "/cache", 1);
  setenv("HOME", "/home/me", 1);
  CHECK(calibration_path() == "/x/mine.json");
  unsetenv("BSMPM_CALIBRATION");
  CHECK(calibration_path() == "/cache/bsmpm/calibration.json");
  unsetenv("XDG_CACHE_HOME");
  CHECK(calibration_path() == "/home/me/.cache/bsmpm/calibration.json");
  unsetenv("HOME");
  CHECK(calibration_path().empty());
  CHECK(this_machine().cores >= 1);
  // The CPU's name as /proc/cpuinfo gives it in its first "model name" line ("unknown" on a
  // machine whose kernel names none), read here with a pattern of its own.
  std::string expected_cpu = "unknown";
  {
    std::ifstream cpuinfo("/proc/cpuinfo");
    const std::regex model("model name\\s*:\\s*(.*\\S)\\s*");
    std::smatch m;
    for (std::string line; std::getline(cpuinfo, line);)
      if (std::regex_match(line, m, model)) {
        expected_cpu = m[1];
        break;
      }
  }
  CHECK(this_machine().cpu == expected_cpu);
}

TEST_CASE("bsmpm bench records its rate, and check and run predict the wall time from it", "[calibration]") {
  const fs::path dir = test::scratch_dir("calibration_round_trip");
  const fs::path file = dir / "cache" / "calibration.json";  // its directory does not exist yet

  // Without a record, check says how to make one (and does not fail).
  auto r = bsmpm_calibrated(file, "check " + kScene + " --threads 1");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(contains(r.output, "wall     no calibration: run `bsmpm bench` once (it records this machine's rate in " +
                               file.string() + ")"));

  r = bsmpm_calibrated(file, "bench " + kScene + " --steps 3 --warmup 1 --threads 1");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(contains(r.output, "calibration          recorded in " + file.string()));
  CalibrationFile read = read_calibration(file.string());
  CHECK(read.warning.empty());
  REQUIRE(read.records.size() == 1);
  const CalibrationRecord first = read.records[0];
  CHECK(first.machine == this_machine());
  CHECK(first.threads == 1);
  CHECK(first.scene == kScene);
  CHECK(first.particles == 6400);
  CHECK(first.rigid_particles == 0);
  CHECK(first.particle_steps_per_second > 0.0);
  CHECK(first.features.order == 2);
  CHECK(first.features.velocity_update == "flip");

  // Another key adds a record; the same key again replaces its record (--json prints the record only).
  REQUIRE(bsmpm_calibrated(file, "bench " + kScene + " --steps 2 --warmup 0 --threads 1 --set grid.order=3").status == 0);
  r = bsmpm_calibrated(file, "bench " + kScene + " --steps 2 --warmup 0 --threads 1 --json");
  REQUIRE(r.status == 0);
  CHECK(!contains(r.output, "calibration"));
  read = read_calibration(file.string());
  REQUIRE(read.records.size() == 2);
  CHECK(read.records[0].recorded_at >= first.recorded_at);
  CHECK(read.records[1].features.order == 3);
  // The records were written beside the file and renamed over it: nothing else is left.
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(file.parent_path())) left.push_back(entry.path().filename().string());
  CHECK(left == std::vector<std::string>{"calibration.json"});

  // check names the record it used; with no record of the scene's order, the nearest one.
  r = bsmpm_calibrated(file, "check " + kScene + " --threads 1");
  const std::string wall = line_starting(r.output, "wall     ");
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(contains(wall, "wall     about "));
  CHECK(contains(wall, " on 1 thread: "));
  CHECK(contains(wall, " frames, from the rate `bsmpm bench " + kScene + "` measured ("));
  CHECK(contains(wall, " M/s, 6400 particles, 1 thread) "));
  CHECK(contains(wall, " ago (same features)"));
  r = bsmpm_calibrated(file, "check " + kScene + " --threads 1 --set grid.order=1");
  CHECK(contains(line_starting(r.output, "wall     "), "; the nearest record: order 2, the run's 1"));

  // The run prints the same line and keeps the prediction beside the actual wall time.
  r = bsmpm_calibrated(file, "run " + kScene + " --out " + (dir / "run").string() +
                                 " --quiet --threads 1 --set time.end=0.002 --set output.frame_interval=0.002");
  REQUIRE(r.status == 0);
  CHECK(contains(r.output, "wall     about "));
  const RunSummary summary = read_run_summary((dir / "run").string());
  CHECK(summary.predicted_wall_seconds > 0.0);
  CHECK(summary.wall_seconds > 0.0);
  // Without a calibration the summary says null.
  REQUIRE(bsmpm_calibrated(dir / "none" / "calibration.json",
                           "run " + kScene + " --out " + (dir / "run_uncalibrated").string() +
                               " --quiet --threads 1 --set time.end=0.002 --set output.frame_interval=0.002")
              .status == 0);
  CHECK(std::isnan(read_run_summary((dir / "run_uncalibrated").string()).predicted_wall_seconds));
  CHECK(contains(test::read_text(dir / "run_uncalibrated" / "summary.json"), "\"predicted_wall_seconds\": null"));
}

TEST_CASE("A calibration file that cannot be read is a warning naming it, not a failure", "[calibration]") {
  const fs::path dir = test::scratch_dir("calibration_corrupt");
  const fs::path file = dir / "cache" / "calibration.json";
  for (const auto& [text, why] : std::vector<std::pair<std::string, std::string>>{
           {"[{\"cpu\": \"x\", \"cores\": 2,", "not a JSON array of flat objects"},
           {"{\"cpu\": \"x\"}", "not a JSON array of flat objects (expected '['"},
           {"[{\"cpu\": \"x\", \"cores\": 2}]", "record 1 has no number \"threads\""},
           {std::string("\0\xff\x01garbage", 10), "not a JSON array of flat objects"}}) {
    write_text(file, text);
    const CalibrationFile read = read_calibration(file.string());
    INFO(read.warning);
    CHECK(read.records.empty());
    CHECK(contains(read.warning, file.string() + ": " + why));
    const auto r = bsmpm_calibrated(file, "check " + kScene + " --threads 1");
    INFO(r.output);
    CHECK(r.status == 0);
    CHECK(contains(r.output, "warning  " + file.string() + ": "));
    CHECK(contains(r.output, "the calibration there is ignored"));
    CHECK(contains(r.output, "wall     no calibration: run `bsmpm bench` once"));
    CHECK(contains(r.output, "ok: 6400 particles"));
  }
  // bench replaces it, saying so.
  const auto r = bsmpm_calibrated(file, "bench " + kScene + " --steps 1 --warmup 0 --threads 1");
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(contains(r.output, "bsmpm: warning: " + file.string() + ": "));
  const CalibrationFile read = read_calibration(file.string());
  CHECK(read.warning.empty());
  CHECK(read.records.size() == 1);
  // A place that cannot be written: the measurement stands, with a warning.
  write_text(dir / "blocked", "a file, not a directory");
  const auto blocked = bsmpm_calibrated(dir / "blocked" / "calibration.json", "bench " + kScene + " --steps 1 --warmup 0 --threads 1");
  INFO(blocked.output);
  CHECK(blocked.status == 0);
  CHECK(contains(blocked.output, "particle-steps/s"));
  CHECK(contains(blocked.output, "bsmpm: warning: the rate is not recorded: " + (dir / "blocked" / "calibration.json").string()));
}

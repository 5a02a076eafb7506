// The command line: help and version, usage errors with their exit codes and messages, an
// output directory that is occupied or cannot be created, and bsmpm bench --json.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "core/version.hpp"
#include "bad_input_check.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

const fs::path& scratch() { return test::scratch_root("cli"); }

// The program, run through `prefix` if given (e.g. "env VAR=value").
test::ProgramResult bsmpm_with(const std::string& args, const std::string& prefix = "") {
  return test::run_program(args, scratch() / "program.log", prefix);
}

using test::contains;

const std::string kScene = test::scene_path("hydrostatic_tank.toml");
// A run of a few steps: enough to start writing, fast to finish (kShortRun without progress).
const std::string kFewSteps = " --set time.end=0.002 --set output.frame_interval=0.002";
const std::string kShortRun = " --quiet" + kFewSteps;

}  // namespace

TEST_CASE("bsmpm --help, a command's --help and --version print and exit 0", "[cli]") {
  const auto help = bsmpm_with("--help");
  CHECK(help.status == 0);
  CHECK(contains(help.output, "usage: bsmpm COMMAND [options]"));
  for (const char* command : {"run", "check", "bench", "render", "movie", "compare", "study", "metrics"}) {
    INFO(command);
    CHECK(contains(help.output, std::string("  ") + command + " "));
    const auto own = bsmpm_with(std::string(command) + " --help");
    CHECK(own.status == 0);
    CHECK(contains(own.output, std::string("usage: bsmpm ") + command));
  }
  const auto version = bsmpm_with("--version");
  CHECK(version.status == 0);
  CHECK(version.output == std::string("bsmpm ") + kVersion + " (" + kGitRevision + ")\n");
  // Without any argument the usage goes to standard error and the status says it was wrong.
  const auto bare = bsmpm_with("");
  CHECK(bare.status == 2);
  CHECK(contains(bare.output, "usage: bsmpm COMMAND"));
}

TEST_CASE("The version names the source tree's current revision, not the one at configure time", "[cli]") {
  // A revision read once when CMake configured went stale with every commit: study cases and
  // resumes would then accept results of other code as this build's. Read at every build, it
  // is HEAD's, with "-dirty.HASH" exactly when tracked files differ from HEAD.
  const fs::path head = scratch() / "head.txt", diff = scratch() / "diff.txt";
  const std::string git = std::string("git -C ") + BSMPM_SOURCE_DIR;
  if (std::system((git + " rev-parse --short=12 HEAD > " + head.string() + " 2>/dev/null").c_str()) != 0) {
    CHECK(std::string(kGitRevision) == "unknown");  // not built from a git checkout
    return;
  }
  REQUIRE(std::system((git + " diff HEAD --quiet; echo $? > " + diff.string()).c_str()) == 0);
  std::string revision = test::read_text(head);
  revision.erase(revision.find_last_not_of("\n") + 1);
  const bool dirty = test::read_text(diff).front() == '1';
  const std::string built = kGitRevision;
  CHECK(built.substr(0, built.find('-')) == revision);
  CHECK((built.find("-dirty.") != std::string::npos) == dirty);
}

TEST_CASE("Usage errors exit 2 with a message naming the problem and write nothing", "[cli]") {
  struct Case {
    std::string args, message;
  };
  const fs::path out = scratch() / "never";
  const std::vector<Case> cases = {
      {"frobnicate", "bsmpm: error: unknown command 'frobnicate' (see bsmpm --help)"},
      {"run " + kScene, "bsmpm: error: run needs --out DIR (see bsmpm run --help)"},
      {"run --out " + out.string(), "bsmpm: error: run expects one scene file"},
      {"run " + kScene + " --out " + out.string() + " --threads two", "--threads expects an integer, got 'two'"},
      {"run " + kScene + " --out " + out.string() + " --threads -1", "--threads expects 1 to 1024, got -1 (without --threads: all "},
      {"run " + kScene + " --out " + out.string() + " --threads 0", "--threads expects 1 to 1024, got 0 (without --threads: all "},
      {"run " + kScene + " --out " + out.string() + " --threads 5000", "--threads expects 1 to 1024, got 5000"},
      {"run " + kScene + " --out " + out.string() + " --threads", "--threads needs a value"},
      {"run " + kScene + " --out " + out.string() + " --fast", "unknown option --fast (see --help)"},
      {"bench " + kScene + " --steps 0", "--steps must be >= 1"},
  };
  for (const Case& c : cases) {
    test::check_bad_input([](const std::string& args) { return bsmpm_with(args); }, c.args, c.message);
    CHECK(!fs::exists(out));
  }
}

TEST_CASE("bsmpm run prints its progress line from the first step on, and none with --quiet", "[cli][quiet]") {
  // The run reports after its first step, whatever the machine's speed, so the line without
  // --quiet is there however fast the run; with --quiet the same run says nothing of it.
  const std::string short_run = " --threads 1" + kFewSteps;
  const auto loud = bsmpm_with("run " + kScene + " --out " + (scratch() / "loud").string() + short_run);
  const auto quiet = bsmpm_with("run " + kScene + " --out " + (scratch() / "quiet").string() + short_run + " --quiet");
  INFO(loud.output);
  INFO(quiet.output);
  REQUIRE(loud.status == 0);
  REQUIRE(quiet.status == 0);
  CHECK(contains(loud.output, "step 1  t = "));
  CHECK(contains(loud.output, " steps/s  ETA "));
  CHECK(!contains(quiet.output, "step 1  t = "));
  CHECK(!contains(quiet.output, " steps/s  ETA "));
}

TEST_CASE("bsmpm run refuses an occupied --out and one that cannot be created", "[cli][output]") {
  SECTION("a directory holding other files, without --force") {
    const fs::path dir = scratch() / "occupied";
    fs::create_directories(dir);
    std::ofstream(dir / "notes.txt") << "keep me\n";
    const auto r = bsmpm_with("run " + kScene + " --out " + dir.string() + kShortRun);
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(contains(r.output, "bsmpm: error: " + dir.string() + " is not empty; choose a new directory or pass --force"));
    CHECK(test::read_text(dir / "notes.txt") == "keep me\n");
    CHECK(!fs::exists(dir / "run.h5"));
  }
  SECTION("a regular file") {
    const fs::path file = scratch() / "a_file";
    std::ofstream(file) << "x";
    const auto r = bsmpm_with("run " + kScene + " --out " + file.string() + kShortRun);
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(contains(r.output, "bsmpm: error: " + file.string() + " exists and is not a directory"));
    CHECK(test::read_text(file) == "x");
  }
  SECTION("a directory below a regular file (cannot be created)") {
    const fs::path file = scratch() / "not_a_directory";
    std::ofstream(file) << "x";
    const fs::path dir = file / "run";
    const auto r = bsmpm_with("run " + kScene + " --out " + dir.string() + kShortRun);
    INFO(r.output);
    CHECK(r.status == 1);  // an I/O failure, not a usage error
    CHECK(contains(r.output, "bsmpm: error: "));
    CHECK(contains(r.output, dir.string()));
    CHECK(contains(r.output, "Not a directory"));
    CHECK(test::read_text(file) == "x");
  }
}

namespace {

// The fields of a JSON object, checked to be valid JSON by Python's parser (a dependency of
// scripts/setup), one "key=value" line each; lists become "a,b", and the members of a nested
// object "key.member=value".
std::map<std::string, std::string> json_fields(const std::string& json) {
  const fs::path in = scratch() / "bench.json", out = scratch() / "bench.fields";
  std::ofstream(in) << json;
  const std::string cmd = "python3 -c \"import json, sys; d = json.load(open(sys.argv[1])); "
                          "[print(k + '=' + (','.join(map(str, v)) if isinstance(v, list) else str(v))) for k, v in d.items() "
                          "if not isinstance(v, dict)]; "
                          "[print(k + '.' + m + '=' + str(u)) for k, v in d.items() if isinstance(v, dict) for m, u in v.items()]\" " +
                          in.string() + " > " + out.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  INFO(test::read_text(out));
  REQUIRE(status == 0);
  std::map<std::string, std::string> fields;
  std::istringstream lines(test::read_text(out));
  for (std::string line; std::getline(lines, line);) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) fields[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return fields;
}

}  // namespace

TEST_CASE("bsmpm bench --json prints one valid JSON object with the run's facts", "[cli][bench]") {
  // A scene path that needs escaping in JSON: a double quote and a backslash in its name.
  const fs::path scene = scratch() / "tank \"quoted\" \\ name.toml";
  fs::copy_file(kScene, scene, fs::copy_options::overwrite_existing);
  // Its own calibration file: a warning about the shared one would be a second line.
  // More threads than cores, so that the two counts differ on any machine; a wait policy of
  // the test's own, not the one its runner sets.
  const unsigned cores = static_cast<unsigned>(sysconf(_SC_NPROCESSORS_ONLN));
  const std::string threads = std::to_string(cores + 1);
  const auto r = bsmpm_with("bench '" + scene.string() + "' --steps 3 --warmup 1 --threads " + threads +
                                " --set time.end=1 --json",
                            "env OMP_WAIT_POLICY=ACTIVE BSMPM_CALIBRATION=" + (scratch() / "calibration.json").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);  // the record (its rate goes to the calibration)
  const auto f = json_fields(r.output);
  CHECK(f.at("scene") == scene.string());
  CHECK(f.at("particles") == "6400");  // 0.2 x 0.2 m of water at 2 x 2 particles per 5 mm cell
  CHECK(f.at("order") == "2");
  CHECK(f.at("cells") == "40,60");
  CHECK(std::stod(f.at("cell_size").substr(0, f.at("cell_size").find(','))) == 0.005);
  CHECK(f.at("threads") == threads);
  CHECK(f.at("cores") == std::to_string(cores));  // the online processors, as sysconf counts them
  CHECK(f.at("steps") == "3");
  // The timings are the machine's (not asserted); they must agree with each other.
  const double seconds = std::stod(f.at("seconds")), per_step = std::stod(f.at("seconds_per_step"));
  const double rate = std::stod(f.at("particle_steps_per_second"));
  CHECK(seconds > 0.0);
  CHECK(per_step == Approx(seconds / 3).epsilon(1e-4));
  CHECK(rate == Approx(6400 * 3 / seconds).epsilon(1e-4));
  CHECK(f.at("overrides") == "time.end=1");
  CHECK(f.at("omp_wait_policy") == "ACTIVE");
  // Memory: the grid has (40 + 2) x (60 + 2) control points at order 2; a particle holds at
  // least its position, velocity, mass, volume, J, F, stress and weights (> 150 bytes).
  CHECK(f.at("control_points") == std::to_string(42 * 62));
  CHECK(std::stod(f.at("bytes_per_particle")) > 150.0);
  CHECK(std::stod(f.at("bytes_per_control_point")) > 50.0);
  // The phases: exclusive, so that they add up to the time per step (to the clock's
  // resolution); this scene's steps have each of these.
  double sum = 0.0;
  std::size_t phases = 0;
  for (const auto& [key, value] : f)
    if (key.rfind("phase_seconds_per_step.", 0) == 0) {
      sum += std::stod(value);
      ++phases;
    }
  for (const char* phase : {"weights", "particle_to_grid", "effects", "grid_update", "grid_to_particle", "stress",
                            "clear_grid"}) {
    INFO(phase);
    CHECK(std::stod(f.at(std::string("phase_seconds_per_step.") + phase)) > 0.0);
  }
  CHECK(sum == Approx(per_step).epsilon(0.01));
  CHECK(f.size() - phases == 16);
}

TEST_CASE("OpenMP threads of bsmpm spin briefly, then sleep, unless the environment says otherwise", "[cli][bench]") {
  // With OMP_DISPLAY_ENV=verbose libgomp prints what it read: a spin count of 1000 then a
  // sleep. ctest sets OMP_WAIT_POLICY for the tests, so each case sets or clears it here.
  const auto brief = bsmpm_with("--version", "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose");
  INFO(brief.output);
  CHECK(brief.status == 0);
  CHECK(contains(brief.output, "GOMP_SPINCOUNT = '1000'"));
  CHECK(contains(brief.output, "bsmpm "));  // the version, printed once by the restarted program
  const auto passive = bsmpm_with("--version", "env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=passive OMP_DISPLAY_ENV=verbose");
  CHECK(contains(passive.output, "GOMP_SPINCOUNT = '0'"));
  const auto active = bsmpm_with("--version", "env OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose");
  CHECK(contains(active.output, "OMP_WAIT_POLICY = 'ACTIVE'"));
  CHECK(!contains(active.output, "GOMP_SPINCOUNT = '1000'"));
  const auto spin =
      bsmpm_with("bench " + kScene + " --steps 1 --warmup 0 --json", "env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=5000");
  CHECK(contains(spin.output, "\"omp_wait_policy\": \"GOMP_SPINCOUNT=5000\""));
  const auto unset = bsmpm_with("bench " + kScene + " --steps 1 --warmup 0 --json", "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT");
  CHECK(contains(unset.output, "\"omp_wait_policy\": \"GOMP_SPINCOUNT=1000\""));
}

TEST_CASE("Checkpoints come every 10 minutes of wall time unless the command or the site says otherwise", "[cli][checkpoint]") {
  struct Case {
    std::string option, environment, plan;
  };
  const std::vector<Case> cases = {
      {"", "env -u BSMPM_CHECKPOINT_EVERY", "checkpt  every 10 min of wall time to "},
      {" --checkpoint-every 1.5h", "env -u BSMPM_CHECKPOINT_EVERY", "checkpt  every 90 min of wall time to "},
      {" --checkpoint-every 0.05s", "env -u BSMPM_CHECKPOINT_EVERY", "checkpt  every 0.05 s of simulated time to "},
      {"", "env BSMPM_CHECKPOINT_EVERY=2000steps", "checkpt  every 2000 steps to "},
      {" --checkpoint-every 0", "env BSMPM_CHECKPOINT_EVERY=2000steps", "checkpt  none (--checkpoint-every 0)"},
  };
  for (const Case& c : cases) {
    const fs::path dir = scratch() / "checkpoint_plan";
    fs::remove_all(dir);
    INFO(c.environment << " bsmpm run" << c.option);
    const auto r = bsmpm_with("run " + kScene + " --out " + dir.string() + kShortRun + c.option, c.environment);
    INFO(r.output);
    CHECK(r.status == 0);
    CHECK(contains(r.output, c.plan));
    if (c.plan.find("none") == std::string::npos)
      CHECK(contains(r.output, "checkpoint.h5, about "));  // its size on the disk
  }
  const auto bad = bsmpm_with("run " + kScene + " --out " + (scratch() / "never").string() + kShortRun,
                              "env BSMPM_CHECKPOINT_EVERY=soon");
  CHECK(bad.status == 2);
  CHECK(contains(bad.output, "$BSMPM_CHECKPOINT_EVERY expects wall-clock time (10min, 1h), simulated seconds (0.05s), "
                             "steps (2000steps) or 0 (never), got 'soon'"));
}

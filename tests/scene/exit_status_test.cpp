// Every exit status the README's table (and bsmpm --help) lists, made to happen, with the
// message that goes with it: the table and the program cannot drift apart.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "io/run_summary.hpp"
#include "bad_input_check.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

using test::contains;

const fs::path& scratch() { return test::scratch_root("exit_status"); }

test::ProgramResult program(const std::string& args, const std::string& prefix = "") {
  return test::run_program(args, scratch() / "program.log", prefix);
}

const std::string kTank = test::scene_path("hydrostatic_tank.toml");
const std::string kLobovsky = test::scene_path("lobovsky_h300.toml");

// The statuses of the README's "Exit status" table.
std::set<int> readme_statuses() {
  const std::string readme = test::read_text(test::source_path("README.md"));
  const auto start = readme.find("## Exit status");
  REQUIRE(start != std::string::npos);
  const std::string section = readme.substr(start, readme.find("\n## ", start + 1) - start);
  std::set<int> statuses;
  const std::regex row(R"(\n\| (\d+) \|)");
  for (std::sregex_iterator m(section.begin(), section.end(), row), end; m != end; ++m)
    statuses.insert(std::stoi((*m)[1]));
  return statuses;
}

// The statuses bsmpm --help lists under "exit status".
std::set<int> help_statuses() {
  const std::string help = program("--help").output;
  const auto start = help.find("exit status (every command)");
  REQUIRE(start != std::string::npos);
  std::set<int> statuses;
  std::istringstream lines(help.substr(start));
  std::string line;
  std::getline(lines, line);
  const std::regex entry(R"(^  (\d+) )");
  for (std::smatch m; std::getline(lines, line);)
    if (std::regex_search(line, m, entry)) statuses.insert(std::stoi(m[1]));
  return statuses;
}

// Starts a run, sends `signal` once it has written a frame after the first, returns the wait
// status and leaves the run in `dir`.
int run_and_signal(const fs::path& dir, int signal) {
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(126);
    execl(BSMPM_EXECUTABLE, BSMPM_EXECUTABLE, "run", kLobovsky.c_str(), "--out", dir.c_str(), "--quiet", "--threads",
          "1", "--set", "grid.cell_size=0.01", "--set", "output.frame_interval=0.002", nullptr);
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline &&
         !contains(fs::exists(dir / "run.xdmf") ? test::read_text(dir / "run.xdmf") : "", "frame 000001"))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

}  // namespace

TEST_CASE("The README and bsmpm --help list the same exit statuses, those tested here", "[cli][exit]") {
  const std::set<int> tested = {0, 1, 2, 3, 4, 130, 143};
  CHECK(readme_statuses() == tested);
  CHECK(help_statuses() == tested);
}

TEST_CASE("Exit 0: done", "[cli][exit]") {
  const auto r = program("check " + kTank);
  CHECK(r.status == 0);
  CHECK(contains(r.output, "ok: 6400 particles"));
}

TEST_CASE("Exit 1: another failure (an I/O error, compare beyond its tolerance)", "[cli][exit]") {
  const fs::path file = scratch() / "a_file";
  std::ofstream(file) << "x";
  const auto io = program("run " + kTank + " --quiet --set time.end=0.002 --out " + (file / "run").string());
  CHECK(io.status == 1);
  CHECK(contains(io.output, "Not a directory"));
  // Two images that differ, beyond a tolerance of none at all.
  const fs::path golden = test::source_path("tests/regression/golden");
  std::vector<fs::path> pngs;
  for (const auto& e : fs::directory_iterator(golden))
    if (e.path().extension() == ".png") pngs.push_back(e.path());
  REQUIRE(pngs.size() >= 2);
  const auto compare = program("compare " + pngs[0].string() + " " + pngs[1].string() + " --tolerance max=0");
  CHECK(compare.status == 1);
  CHECK((contains(compare.output, "result: exceeds the tolerance") || contains(compare.output, "differ in size")));
}

TEST_CASE("Exit 2: bad input, each with a message that says what and where", "[cli][exit]") {
  // A run file cut short, as a crash or a full disk left them before the room was kept.
  const fs::path run = scratch() / "truncated";
  REQUIRE(program("run " + kTank + " --quiet --set time.end=0.01 --set output.frame_interval=0.005 --out " + run.string())
              .status == 0);
  fs::resize_file(run / "run.h5", fs::file_size(run / "run.h5") / 2);
  const fs::path dir = scratch() / "a_directory.toml";
  fs::create_directories(dir);
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"frobnicate", "unknown command 'frobnicate'"},
      {"check /no/such/scene.toml", "/no/such/scene.toml: cannot read the scene file: No such file or directory"},
      {"check " + dir.string(), dir.string() + ": cannot read the scene file: it is a directory"},
      {"check " + kTank + " --set grid.cel_size=1", "--set grid.cel_size: grid.cel_size: unknown key (did you mean 'cell_size'?)"},
      {"check " + kTank + " --set foo.bar=1", "--set foo.bar: foo: unknown key"},
      {"run " + kTank + " --out " + (scratch() / "never").string() + " --threads 0", "--threads expects 1 to 1024, got 0"},
      {"check " + kLobovsky + " --set grid.cell_size=0.0001", "of memory; this machine has"},
      {"metrics " + run.string() + " --stripes 0.05", "--stripes expects two numbers A,B with A < B, got \"0.05\""},
      {"metrics " + run.string() + " --stripes 0,0.05 --time 1,2 --time-star 1,2", "give --time or --time-star, not both"},
      {"metrics " + run.string() + " --series P_depth50",
       run.string() + "/run.h5: cannot open as an HDF5 file (HDF5: truncated file: "},
      {"render " + (run / "run.h5").string() + " --out " + (scratch() / "frame.png").string(),
       "the file is damaged (h5ls cannot open it either)"},
      {"render " + (run / "run.h5").string() + " --out " + (scratch() / "frame.jpg").string(),
       "render writes PNG images; give FILE.png for one image"},
  };
  for (const Case& c : cases) {
    const std::string output = test::check_bad_input([](const std::string& args) { return program(args); }, c.args,
                                                       c.message);
    CHECK(!contains(output, "still writing it"));  // a damaged file is not said to be a run being written
  }
  CHECK(!fs::exists(scratch() / "frame.jpg"));  // no directory of that name either
  CHECK(!fs::exists(scratch() / "never"));
}

TEST_CASE("Exit 3: numerical instability, the frames kept", "[cli][exit]") {
  const fs::path dir = scratch() / "unstable";
  const auto r = program("run " + kLobovsky + " --out " + dir.string() +
                       " --quiet --threads 1 --set grid.cell_size=0.02 --set time.end=0.2 "
                       "--set solver.density_range=[0.999,1.001]");
  CHECK(r.status == 3);
  CHECK(contains(r.output, "numerical instability at step "));
  CHECK(read_run_summary(dir.string()).exit_status == 3);
}

TEST_CASE("Exit 3: an incompressible fluid's pressure solve that does not converge, the frames kept",
          "[cli][exit][incompressible]") {
  // Two iterations cannot bring the first solve (about 50 from the particles' pressure) to
  // the tolerance: the run stops at its first step, saying which solve and why.
  const fs::path dir = scratch() / "unconverged";
  const auto r = program("run " + test::scene_path("hydrostatic_tank_incompressible.toml") + " --out " +
                         dir.string() + " --quiet --threads 1 --set time.end=0.01 --set solver.pressure.max_iterations=2");
  INFO(r.output);
  CHECK(r.status == 3);
  CHECK(contains(r.output, "the pressure solve of the incompressible fluid did not converge"));
  CHECK(contains(r.output, "after 2 conjugate-gradient iterations"));
  CHECK(read_run_summary(dir.string()).exit_status == 3);
  CHECK(fs::exists(dir / "run.h5"));  // the frames so far and the failing state
}

TEST_CASE("Exit 4: out of space, every file whole", "[cli][exit]") {
  const fs::path dir = scratch() / "full";
  const auto r = program("run " + kLobovsky + " --out " + dir.string() +
                           " --quiet --threads 1 --force --set grid.cell_size=0.02 --set time.end=0.1",
                       "prlimit --fsize=614400 --");
  CHECK(r.status == 4);
  CHECK(contains(r.output, "bsmpm: error: out of space: " + dir.string() + "/run.h5: no room for the next frame"));
  CHECK(read_run_summary(dir.string()).exit_status == 4);
}

TEST_CASE("Exit 130 and 143: interrupted by SIGINT or SIGTERM, resumable", "[cli][exit]") {
  const int signal = GENERATE(SIGINT, SIGTERM);
  const fs::path dir = scratch() / ("signal_" + std::to_string(signal));
  const int status = run_and_signal(dir, signal);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + signal);
  CHECK(read_run_summary(dir.string()).exit_status == 128 + signal);
  CHECK(fs::exists(dir / "checkpoint.h5"));
}

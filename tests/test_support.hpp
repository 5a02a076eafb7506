// Helpers shared by the test suites: repository paths, running the program (or a script) and
// checking what it said, and running a scene in-process.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "scene/scene_builder.hpp"
#include "scene/scene_loader.hpp"
#include "step/run_loop.hpp"
#include "step/time_step.hpp"

namespace bsmpm::test {

inline std::string source_path(const std::string& relative) { return std::string(BSMPM_SOURCE_DIR) + "/" + relative; }
inline std::string scene_path(const std::string& name) { return source_path("scenes/" + name); }
// A test fixture: a small scene several tests (or one test, kept out of its code) run, in
// tests/scenes/.
inline std::string fixture_path(const std::string& name) { return source_path("tests/scenes/" + name); }

// An empty directory `name` in this test process's scratch space (under the system's temp
// directory); the whole scratch space is removed when the process exits.
inline std::filesystem::path scratch_dir(const std::string& name) {
  namespace fs = std::filesystem;
  struct Scratch {
    fs::path root = fs::temp_directory_path() / ("bsmpm_test_" + std::to_string(::getpid()));
    ~Scratch() {
      std::error_code ignored;
      fs::remove_all(root, ignored);
    }
  };
  static const Scratch scratch;
  const fs::path d = scratch.root / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// scratch_dir(name), made on the first call and the same directory on every later one: a test
// file's scratch space, which its tests share.
inline const std::filesystem::path& scratch_root(const std::string& name) {
  static std::map<std::string, std::filesystem::path> made;
  auto it = made.find(name);
  if (it == made.end()) it = made.emplace(name, scratch_dir(name)).first;
  return it->second;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// What the program did: its exit status (-1 if it did not exit, e.g. killed by a signal)
// and its standard output and error, interleaved.
struct ProgramResult {
  int status = -1;
  std::string output;
};

// Runs a shell command line with its standard output and error into `log`.
inline ProgramResult run_shell(const std::string& command, const std::filesystem::path& log) {
  const int status = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(log)};
}

// Runs the built program with `args` (a shell command line), its output kept in `log`;
// through `prefix` if given (e.g. "env NAME=VALUE", "prlimit --as=N --").
inline ProgramResult run_program(const std::string& args, const std::filesystem::path& log,
                                 const std::string& prefix = "") {
  return run_shell(prefix + (prefix.empty() ? "" : " ") + BSMPM_EXECUTABLE + " " + args, log);
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Loads scenes/NAME with overrides, builds and runs it to its end time.
struct SceneRun {
  SceneDescription scene;
  std::unique_ptr<Simulation> sim;
  RunOutcome outcome;
};

inline SceneRun run_scene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  SceneRun r;
  r.scene = load_scene(scene_path(name), overrides);
  r.sim = build_simulation(r.scene);
  r.outcome = run_to_end(*r.sim, r.scene.time, r.scene.frame_interval, RunHooks{});
  return r;
}

// Advances a built scene step by step to its end time with the scene's time step, calling
// after_step(sim) after every step.
template <class F>
void step_through(Simulation& sim, const SceneDescription& scene, F&& after_step) {
  const GridInfo g = sim.grid_info();
  const double h_min = std::min(g.cell_size.x(), g.cell_size.y());
  while (sim.time() < scene.time.end) {
    sim.advance(time_step(scene.time, sim.max_signal_speed(), h_min));
    after_step(sim);
  }
}

// The probe called `name`, or nullptr.
inline const Probe* find_probe(const Simulation& sim, const std::string& name) {
  for (const auto& p : sim.probes())
    if (p->name() == name) return p.get();
  return nullptr;
}

// The lowest P* (column 3) a pressure probe reads from its first sample above `contact` on;
// none if it never reads above it.
inline std::optional<double> lowest_after_contact(const Probe& probe, double contact) {
  std::optional<double> lowest;
  for (std::size_t r = 0; r < probe.row_count(); ++r) {
    const double p_star = probe.row(r)[3];
    if (lowest || p_star > contact) lowest = std::min(lowest.value_or(p_star), p_star);
  }
  return lowest;
}

}  // namespace bsmpm::test

// Guards before and during a run: a scene too large for the machine, or whose time step is
// absurdly small, is refused at once with the numbers (exit 2); a particle leaving the
// density range stops the run within its step, naming step, time, body, particle and field,
// after a final frame and a checkpoint of the failing state. And the cost prediction they
// all read, against real runs: steps, output size and memory.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/hdf5.hpp"
#include "io/run_summary.hpp"
#include "scene/run_guards.hpp"
#include "study/program_runner.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

std::string program() { return std::string(BSMPM_EXECUTABLE); }

}  // namespace

TEST_CASE("check refuses at once a scene that would not fit in memory, with the numbers", "[guards]") {
  // The Lobovsky tank at a 0.1 mm grid: 72 million particles; the guard answers before seeding.
  const fs::path log = test::scratch_dir("guard_memory") / "log";
  const auto start = std::chrono::steady_clock::now();
  const int code = test::run_command(program() + " check " + test::scene_path("lobovsky_h300.toml") +
                                         " --set grid.cell_size=0.0001", log);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string text = test::read_text(log);
  INFO(text);
  CHECK(code == 2);
  CHECK(text.find("7.2e+07 particles") != std::string::npos);
  CHECK(text.find("of memory; this machine has") != std::string::npos);
  CHECK(seconds < 5.0);  // measured 0.02 s; it took more than 20 s before the guard
}

TEST_CASE("run refuses a material whose sound speed makes the step absurdly small", "[guards]") {
  const fs::path dir = test::scratch_dir("guard_stiff");
  const int code = test::run_command(program() + " run " + test::scene_path("hydrostatic_tank.toml") + " --out " +
                                         (dir / "run").string() + " --set materials.water.bulk_modulus=1e30",
                                     dir / "log");
  const std::string text = test::read_text(dir / "log");
  INFO(text);
  CHECK(code == 2);
  CHECK(text.find("time steps to t =") != std::string::npos);
  CHECK(text.find("body 'water' carries waves at 3.162e+13 m/s") != std::string::npos);
  CHECK(!fs::exists(dir / "run"));  // nothing written
}

TEST_CASE("The output guard refuses what the disk cannot hold, and warns of long runs", "[guards]") {
  const SceneDescription scene = load_scene(test::scene_path("lobovsky_h300.toml"));
  const RunCost cost = predict_run_cost(scene);
  MachineResources machine;
  machine.available_memory_bytes = 1e12;
  machine.free_disk_bytes = 0.5 * cost.output_bytes;
  CHECK_THROWS_AS(check_run_cost(scene, cost, machine, false), ResourceError);
  machine.free_disk_bytes = 10.0 * cost.output_bytes;
  CHECK(check_run_cost(scene, cost, machine, true).empty());
  // A fixed step far beyond the acoustic limit is warned about.
  SceneDescription fixed = scene;
  fixed.time.mode = TimeStepSettings::Mode::kFixed;
  fixed.time.dt = 10.0 * cost.stable_dt;
  const auto warnings = check_run_cost(fixed, predict_run_cost(fixed), machine, false);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("expect the run to become unstable") != std::string::npos);
}

TEST_CASE("A particle leaving the density range stops the run within its step, named", "[guards]") {
  // A narrow range that the dam break leaves within a few steps of its first motion.
  const fs::path dir = test::scratch_dir("guard_density");
  const int code = test::run_command(program() + " run " + test::scene_path("lobovsky_h300.toml") + " --out " +
                                         (dir / "run").string() +
                                         " --quiet --threads 1 --set grid.cell_size=0.02 --set time.end=0.2"
                                         " --set solver.density_range=[0.999,1.001]",
                                     dir / "log");
  const std::string text = test::read_text(dir / "log");
  INFO(text);
  CHECK(code == 3);
  CHECK(text.find("numerical instability at step ") != std::string::npos);
  CHECK(text.find("body 'water', particle ") != std::string::npos);
  CHECK(text.find("is outside the range [0.999, 1.001] rho0") != std::string::npos);
  // The failing state is the last frame, and a checkpoint for inspection.
  CHECK(fs::exists(dir / "run" / "checkpoint_failed.h5"));
  h5::Handle f = h5::open_file((dir / "run" / "run.h5").string());
  CHECK(h5::get_string_attribute(f, "status").rfind("failed: numerical instability", 0) == 0);
  CHECK(h5::get_long_attribute(f, "frames_written") >= 2);
}

TEST_CASE("The cost prediction matches a short run", "[guards][cost]") {
  const std::vector<std::string> overrides = {"time.end=0.05", "output.frame_interval=0.01"};
  const SceneDescription scene = load_scene(test::scene_path("hydrostatic_tank.toml"), overrides);
  const RunCost cost = predict_run_cost(scene);
  auto sim = build_simulation(scene);
  const RunOutcome outcome = run_to_end(*sim, scene.time, scene.frame_interval, RunHooks{});
  CHECK(cost.particles == static_cast<double>(sim->particles().size()));  // rectangles: exact
  CHECK(cost.frames == 6.0);
  // Steps within 10 % (the water starts at rest: its speed stays below the free-fall bound).
  CHECK(std::abs(cost.steps - outcome.steps) <= 0.1 * outcome.steps);
  // Output within 25 %: the same run through the program.
  const fs::path dir = test::scratch_dir("cost_output") / "run";
  std::string sets;
  for (const auto& o : overrides) sets += " --set " + o;
  REQUIRE(test::run_command(program() + " run " + test::scene_path("hydrostatic_tank.toml") + " --out " + dir.string() +
                                " --quiet --threads 1" + sets,
                            dir.string() + ".log") == 0);
  double bytes = 0.0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != "summary.json") bytes += static_cast<double>(fs::file_size(e.path()));
  INFO("predicted " << cost.output_bytes << " bytes, written " << bytes);
  CHECK(std::abs(cost.output_bytes - bytes) <= 0.25 * bytes);
  // Memory within 25 %: the run's peak resident memory (summary.json), mostly the program
  // here (measured: 80.6 MiB predicted for 81.6 MiB, ratio 0.99); and the increase from this
  // run to one of 25 times its particles (160,000 at a 1 mm grid, a few steps), the part the
  // particles and the grid take (measured: 62.5 MiB predicted for 67.8 MiB, ratio 0.92).
#if defined(__SANITIZE_ADDRESS__)
  // Under AddressSanitizer (scripts/test --sanitize) the resident memory is ASan's (shadow
  // memory, quarantine, redzones: 1.9 times the prediction measured), not the program's, so
  // there is no claim to check; the Release suite checks it.
  return;
#endif
  const double mib = 1024.0 * 1024.0;
  const double peak = read_run_summary(dir.string()).peak_memory_mb * mib;
  INFO("predicted " << cost.memory_bytes / mib << " MiB, peak resident " << peak / mib << " MiB");
  CHECK(std::abs(cost.memory_bytes - peak) <= 0.25 * peak);
  const std::vector<std::string> fine = {"grid.cell_size=0.001", "time.end=0.0006", "output.frame_interval=0.0006"};
  const RunCost fine_cost = predict_run_cost(load_scene(test::scene_path("hydrostatic_tank.toml"), fine));
  const fs::path fine_dir = test::scratch_dir("cost_memory") / "run";
  REQUIRE(fine_cost.steps > 60);  // past a re-sort by cell (every 50 steps), whose buffers count
  REQUIRE(test::run_command(program() + " run " + test::scene_path("hydrostatic_tank.toml") + " --out " +
                                fine_dir.string() + " --quiet --threads 1 --set " + fine[0] + " --set " + fine[1] +
                                " --set " + fine[2],
                            fine_dir.string() + ".log") == 0);
  const double fine_peak = read_run_summary(fine_dir.string()).peak_memory_mb * mib;
  const double predicted_increase = fine_cost.memory_bytes - cost.memory_bytes, increase = fine_peak - peak;
  INFO("predicted increase " << predicted_increase / mib << " MiB, measured " << increase / mib << " MiB");
  CHECK(std::abs(predicted_increase - increase) <= 0.25 * increase);
}

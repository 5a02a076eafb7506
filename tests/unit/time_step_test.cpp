// Time-step control (docs/method.md §7): the CFL rule dt = C h_min / max_p (c_p + |v_p|) with
// the material's wave speed at the current state, its cap max_dt, a fixed dt, and the run
// loop that lands the steps on the frame times.
#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"

using namespace bsmpm;

TEST_CASE("time_step: the CFL rule, its cap and a fixed step", "[time_step]") {
  TimeStepSettings s;
  s.cfl = 0.3;
  s.max_dt = 1e-3;
  CHECK(time_step(s, 40.0, 0.01) == 0.3 * 0.01 / 40.0);
  CHECK(time_step(s, 1.0, 0.01) == 1e-3);  // 3e-3 capped
  CHECK(time_step(s, 0.0, 0.01) == 1e-3);  // nothing moves and nothing carries a wave
  s.mode = TimeStepSettings::Mode::kFixed;
  s.dt = 2.5e-5;
  CHECK(time_step(s, 1e6, 0.01) == 2.5e-5);
  CHECK(time_step(s, 0.0, 0.01) == 2.5e-5);
}

namespace {

}  // namespace

TEST_CASE("The CFL signal speed is the largest wave speed plus particle speed", "[time_step]") {
  const SceneDescription scene = load_scene(test::fixture_path("two_blocks.toml"), {"time.cfl=0.3", "time.max_dt=1.0e-3"});
  const auto sim = build_simulation(scene);
  // Water: c = sqrt(K / rho0 (rho / rho0)^6) at the deepest particle, whose pressure is
  // rho0 g depth (depth 0.2 m less half a spacing). Rubber: the P-wave speed
  // sqrt((lambda + 2 mu) / rho0) = sqrt(4e6 * 0.7 / (1.3 * 0.4) / 1200) = 66.99 m/s, plus 2 m/s.
  const auto& water = std::get<WeaklyCompressibleFluid>(scene.bodies[0].material);
  const double deepest = water.volume_ratio(1000.0 * 9.81 * (0.2 - 0.0025));
  const double c_water = std::sqrt(1e6 / 1000.0 * std::pow(1.0 / deepest, 6));
  const double c_rubber = std::sqrt(4e6 * 0.7 / (1.3 * 0.4) / 1200.0);
  REQUIRE(c_rubber + 2.0 > c_water);
  CHECK(sim->max_signal_speed() == Approx(c_rubber + 2.0).epsilon(1e-12));
  CHECK(time_step(scene.time, sim->max_signal_speed(), 0.01) == Approx(0.3 * 0.01 / (c_rubber + 2.0)).epsilon(1e-12));
  // Without the block, the water's sound speed at its deepest particle bounds the step.
  const SceneDescription water_only =
      load_scene(test::fixture_path("two_blocks.toml"),
                 {"time.cfl=0.3", "time.max_dt=1.0e-3", "bodies[1].material=water", "bodies[1].velocity=[0.0, 0.0]"});
  const auto sim_water = build_simulation(water_only);
  CHECK(sim_water->max_signal_speed() == Approx(c_water).epsilon(1e-9));
}

TEST_CASE("A run takes CFL steps, capped ones, or the fixed step, and lands on the frame times", "[time_step]") {
  struct Case {
    std::vector<std::string> time_step;  // overrides of [time]
    double expected_dt;  // of every step that does not land on a frame time
  };
  const double cfl_dt = 0.3 * 0.01 / (std::sqrt(4e6 * 0.7 / (1.3 * 0.4) / 1200.0) + 2.0);  // 4.34e-5 s at the start
  const std::vector<Case> cases = {
      {{"time.cfl=0.3", "time.max_dt=1.0e-3"}, cfl_dt},  // CFL (the block's speed changes little in 10 ms)
      {{"time.cfl=0.3", "time.max_dt=2.0e-5"}, 2e-5},    // capped
      {{"time.dt=3.0e-5"}, 3e-5},                        // fixed
  };
  for (const Case& c : cases) {
    INFO(c.time_step[0]);
    const SceneDescription scene = load_scene(test::fixture_path("two_blocks.toml"), c.time_step);
    auto sim = build_simulation(scene);
    std::vector<double> frame_times;
    RunHooks hooks;
    hooks.on_frame = [&](const Simulation& s, double) { frame_times.push_back(s.time()); };
    const RunOutcome out = run_to_end(*sim, scene.time, scene.frame_interval, hooks);
    CHECK(out.min_dt == Approx(c.expected_dt).epsilon(0.01));
    CHECK(out.max_dt == Approx(c.expected_dt).epsilon(0.01));
    // Frames at exactly 0, 4 and 8 ms, and the run ends at exactly 10 ms (not a frame time;
    // the run file adds the final state): the steps before them are shortened.
    REQUIRE(frame_times.size() == 3);
    CHECK(frame_times[0] == 0.0);
    CHECK(frame_times[1] == Approx(0.004).epsilon(1e-12));
    CHECK(frame_times[2] == Approx(0.008).epsilon(1e-12));
    CHECK(sim->time() == Approx(0.01).epsilon(1e-12));
    // Every step at most the expected one: the count is at least the whole time over it.
    CHECK(out.steps >= static_cast<long>(0.01 / (c.expected_dt * 1.01)));
  }
  // A fixed step is exactly that step.
  const SceneDescription fixed = load_scene(test::fixture_path("two_blocks.toml"), {"time.dt=3.0e-5"});
  auto sim = build_simulation(fixed);
  const RunOutcome out = run_to_end(*sim, fixed.time, fixed.frame_interval, RunHooks{});
  CHECK(out.min_dt == 3e-5);
  CHECK(out.max_dt == 3e-5);
}

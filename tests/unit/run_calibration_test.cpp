// The wall-time prediction's pure part (scene/run_calibration.hpp): the features of a scene,
// the newest record per key, the choice of the record that fits a run best, and the
// arithmetic. No clock and no files: the records are made here.
#include <catch2/catch.hpp>

#include <algorithm>

#include "scene/run_calibration.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

const MachineIdentity kHere{"Test CPU @ 2.80GHz", 2};

RateFeatures features_of(const std::string& scene, const std::vector<std::string>& overrides = {}) {
  const SceneDescription s = load_scene(test::scene_path(scene), overrides);
  return rate_features(s, predict_run_cost(s));
}

CalibrationRecord record(int threads, RateFeatures f, double rate, double recorded_at,
                         MachineIdentity machine = kHere) {
  CalibrationRecord r;
  r.machine = std::move(machine);
  r.threads = threads;
  r.features = std::move(f);
  r.particle_steps_per_second = rate;
  r.particles = 28800;
  r.scene = "scenes/lobovsky_h300.toml";
  r.recorded_at = recorded_at;
  return r;
}

bool mentions(const std::vector<std::string>& differences, const std::string& part) {
  return std::any_of(differences.begin(), differences.end(),
                     [&](const std::string& d) { return d.find(part) != std::string::npos; });
}

}  // namespace

TEST_CASE("rate_features: what in a scene changes the time per particle-step", "[calibration]") {
  const RateFeatures lobovsky = features_of("lobovsky_h300.toml");
  CHECK(lobovsky.order == 2);
  CHECK(lobovsky.materials == "fluid");
  CHECK(lobovsky.fluid_volume == "smoothed");
  CHECK(lobovsky.velocity_update == "apic");
  CHECK(lobovsky.shifting);
  CHECK(lobovsky.grid_fields == 1);
  const RateFeatures tank = features_of("hydrostatic_tank.toml", {"grid.order=3"});
  CHECK(tank.order == 3);
  CHECK(tank.fluid_volume == "particle");
  CHECK(tank.velocity_update == "flip");
  CHECK(!tank.shifting);
  // Water against an elastic gate in contact: two velocity fields.
  const RateFeatures gate = features_of("elastic_gate.toml");
  CHECK(gate.materials == "elastic+fluid");
  CHECK(gate.grid_fields == 2);
  // Without fluid, the fluid's options do not matter.
  const RateFeatures blocks = features_of("approaching_blocks.toml");
  CHECK(blocks.materials == "elastic");
  CHECK(blocks.fluid_volume == "none");
}

TEST_CASE("merge_calibration keeps the newest record of each key", "[calibration]") {
  const RateFeatures f = features_of("lobovsky_h300.toml");
  std::vector<CalibrationRecord> records;
  records = merge_calibration(records, record(1, f, 5e6, 100.0));
  records = merge_calibration(records, record(2, f, 9e6, 100.0));
  REQUIRE(records.size() == 2);  // a thread count is a key of its own
  records = merge_calibration(records, record(1, f, 6e6, 200.0));
  REQUIRE(records.size() == 2);
  CHECK(records[0].particle_steps_per_second == 6e6);
  records = merge_calibration(records, record(1, f, 4e6, 150.0));  // older than what is kept
  CHECK(records[0].particle_steps_per_second == 6e6);
  RateFeatures order3 = f;
  order3.order = 3;
  CHECK(merge_calibration(records, record(1, order3, 3e6, 300.0)).size() == 3);
  CHECK(merge_calibration(records, record(1, f, 3e6, 300.0, {"Other CPU", 2})).size() == 3);
}

TEST_CASE("choose_calibration: the same key, else the nearest, the newest among equals", "[calibration]") {
  const RateFeatures run = features_of("lobovsky_h300.toml");
  RateFeatures flip = run;
  flip.velocity_update = "flip";
  RateFeatures order3 = run;
  order3.order = 3;

  CHECK(!choose_calibration({}, kHere, 1, run));

  const std::vector<CalibrationRecord> records = {
      record(1, flip, 1e6, 100.0), record(1, run, 2e6, 100.0), record(2, run, 3e6, 100.0),
      record(1, order3, 4e6, 100.0), record(1, run, 5e6, 100.0, {"Other CPU", 8})};
  auto exact = choose_calibration(records, kHere, 1, run);
  REQUIRE(exact);
  CHECK(exact->record->particle_steps_per_second == 2e6);
  CHECK(exact->differences.empty());
  exact = choose_calibration(records, kHere, 2, run);
  REQUIRE(exact);
  CHECK(exact->record->particle_steps_per_second == 3e6);

  // No record at order 1: a feature differs sooner than the threads or the machine.
  RateFeatures order1 = run;
  order1.order = 1;
  const auto near = choose_calibration(records, kHere, 1, order1);
  REQUIRE(near);
  CHECK(near->record->particle_steps_per_second == 2e6);
  CHECK(near->differences == std::vector<std::string>{"order 2, the run's 1"});

  // Four threads: the nearest thread count of this machine, said so.
  const auto threads = choose_calibration(records, kHere, 4, run);
  REQUIRE(threads);
  CHECK(threads->record->particle_steps_per_second == 3e6);
  CHECK(threads->differences == std::vector<std::string>{"2 threads, the run's 4"});

  // On another machine only its records exist.
  const auto elsewhere = choose_calibration(records, {"Third CPU", 4}, 1, run);
  REQUIRE(elsewhere);
  CHECK(mentions(elsewhere->differences, "measured on another machine"));

  // Equal distance: the newer record.
  const std::vector<CalibrationRecord> two = {record(1, flip, 1e6, 100.0), record(1, flip, 7e6, 50.0)};
  CHECK(choose_calibration(two, kHere, 1, run)->record->particle_steps_per_second == 1e6);
  // A record without a positive rate is never chosen.
  CHECK(!choose_calibration({record(1, run, 0.0, 100.0)}, kHere, 1, run));
}

TEST_CASE("predict_wall_time: particle-steps at the record's rate, scaled to the run's features, and frames",
          "[calibration]") {
  RunCost cost;
  cost.particles = 28800;
  cost.steps = 2500;
  cost.particle_steps = cost.particles * cost.steps;
  cost.frames = 10;
  const RateFeatures plain;
  CHECK(relative_cost(plain) == 1.0);
  const CalibrationRecord r = record(1, plain, 7.2e6, 0.0);
  const WallTime same = predict_wall_time(cost, plain, r);
  CHECK(same.particle_steps_per_second == Approx(7.2e6).epsilon(1e-12));
  CHECK(same.stepping_seconds == Approx(10.0).epsilon(1e-12));
  // A frame: 2.5 ms and 1 us per particle (measured; run_calibration.hpp): 10 x 31.3 ms.
  CHECK(same.frame_seconds == Approx(0.313).epsilon(1e-12));
  CHECK(same.seconds == Approx(same.stepping_seconds + same.frame_seconds).epsilon(1e-12));

  // Each feature multiplies by its measured factor (docs/validation.md, "Predicted wall
  // time"): the Lobovsky tank's APIC 1.34 x smoothing 1.31 x shifting 1.27 = 2.229358, order 3
  // another 1.34, a second grid field 1.09; a record of costlier features runs the plain
  // scene faster by their ratio.
  const RateFeatures lobovsky = features_of("lobovsky_h300.toml");
  CHECK(relative_cost(lobovsky) == Approx(2.229358).epsilon(1e-12));
  RateFeatures order3 = lobovsky;
  order3.order = 3;
  CHECK(relative_cost(order3) == Approx(2.98733972).epsilon(1e-12));
  RateFeatures two_fields = plain;
  two_fields.grid_fields = 2;
  CHECK(relative_cost(two_fields) == Approx(1.09).epsilon(1e-12));
  // Incompressible water: a kind of its own (its records apart from the weakly compressible
  // model's), each step the pressure solve's kIncompressibleCost times the explicit step's.
  const RateFeatures incompressible = features_of("lobovsky_h300_incompressible.toml");
  CHECK(incompressible.materials == "incompressible");
  CHECK(relative_cost(incompressible) == Approx(1.34 * 1.27 * kIncompressibleCost).epsilon(1e-12));
  const WallTime from_costlier = predict_wall_time(cost, plain, record(1, lobovsky, 7.2e6, 0.0));
  CHECK(from_costlier.stepping_seconds == Approx(10.0 / 2.229358).epsilon(1e-12));
  CHECK(from_costlier.particle_steps_per_second == Approx(7.2e6 * 2.229358).epsilon(1e-12));

  // Rigid particles are cheaper than deformable ones (0.65 of one, measured), in the record
  // and in the run: half rigid, 0.825 of the work.
  RunCost half_rigid = cost;
  half_rigid.rigid_particles = cost.particles / 2;
  CHECK(predict_wall_time(half_rigid, plain, r).stepping_seconds == Approx(8.25).epsilon(1e-12));
  CalibrationRecord rigid_record = r;
  rigid_record.rigid_particles = r.particles / 2;
  CHECK(predict_wall_time(cost, plain, rigid_record).stepping_seconds == Approx(10.0 / 0.825).epsilon(1e-12));
}

TEST_CASE("format_age: seconds, minutes, hours, days", "[calibration]") {
  CHECK(format_age(40.0) == "40 s");
  CHECK(format_age(12 * 60.0) == "12 min");
  CHECK(format_age(3.2 * 3600.0) == "3.2 h");
  CHECK(format_age(5 * 86400.0) == "5 days");
  CHECK(format_age(-3.0) == "0 s");  // a clock set back
}

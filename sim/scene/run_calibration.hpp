// The wall time of a run before it starts: its predicted particle-steps (run_cost.hpp)
// divided by a rate this machine measured (`bsmpm bench` records one per machine, thread
// count and scene features in the calibration file, calibration_file.hpp). What changes
// the rate is the key of a record: the machine, the threads, and the features of a scene
// that change the work per particle. This file is the pure part: the key of a scene, the
// choice of a record and the arithmetic; no clock, no files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/run_cost.hpp"
#include "scene/scene_description.hpp"

namespace bsmpm {

// The machine a rate was measured on.
struct MachineIdentity {
  std::string cpu;  // "model name" of /proc/cpuinfo
  int cores = 0;    // hardware threads
  bool operator==(const MachineIdentity&) const = default;
};

// What in a scene changes the time per particle-step.
struct RateFeatures {
  int order = 2;                      // spline order: (P + 1)^2 nodes per particle
  std::string materials = "fluid";    // the deformable kinds present: "fluid", "elastic", "elastic+fluid"
  std::string fluid_volume = "none";  // "particle", "smoothed", "projected"; "none" without fluid
  std::string velocity_update = "flip";  // "flip" or "apic"
  bool shifting = false;              // particle shifting (a pass over the particles)
  int grid_fields = 1;                // velocity fields (contact: one per body)
  bool operator==(const RateFeatures&) const = default;
};

RateFeatures rate_features(const SceneDescription& scene, const RunCost& cost);

// One measured rate (a `bsmpm bench` run).
struct CalibrationRecord {
  MachineIdentity machine;
  int threads = 1;
  RateFeatures features;
  double particle_steps_per_second = 0.0;
  double particles = 0.0;    // of the benchmarked scene
  std::string scene;         // the benchmarked scene file
  double recorded_at = 0.0;  // seconds since the Unix epoch
  std::string program_version;
};

// Records with the same key measure the same thing: the newest replaces the older.
std::string calibration_key(const CalibrationRecord& record);

// `records` with `fresh` added, keeping the newest record of each key (order kept otherwise).
std::vector<CalibrationRecord> merge_calibration(std::vector<CalibrationRecord> records, const CalibrationRecord& fresh);

// The record that best fits a run: the same machine, threads and features if there is one,
// else the nearest (a different machine weighs most, then the threads, then each feature),
// the newest among equals. `differences` names what is not the run's ("order 3, the run's 2").
struct CalibrationChoice {
  const CalibrationRecord* record = nullptr;
  std::vector<std::string> differences;
};
std::optional<CalibrationChoice> choose_calibration(const std::vector<CalibrationRecord>& records,
                                                    const MachineIdentity& machine, int threads,
                                                    const RateFeatures& features);

// Predicted wall seconds of the run's stepping: particle-steps at the record's rate.
double predicted_wall_seconds(const RunCost& cost, const CalibrationRecord& record);

// "40 s", "12 min", "3.2 h", "5 days": the age of a record.
std::string format_age(double seconds);

}  // namespace bsmpm

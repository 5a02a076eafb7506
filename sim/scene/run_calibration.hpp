// The wall time of a run before it starts: its predicted particle-steps (run_cost.hpp) at a
// rate this machine measured (`bsmpm bench` records one per machine, thread count and scene
// features in the calibration file, calibration_file.hpp), and its frames. What changes the
// rate is the key of a record: the machine, the threads, and the features of a scene that
// change the work per particle. A record of other features is scaled by the relative cost
// of the features (relative_cost, measured with `bsmpm bench`; docs/validation.md,
// "Predicted wall time"). This file is the pure part: the key of a scene, the choice of a
// record and the arithmetic; no clock, no files.
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
  std::string materials = "fluid";    // the deformable kinds present: "fluid" (or "incompressible"), "elastic", "elastic+fluid"
  std::string fluid_volume = "none";  // "particle", "smoothed", "projected"; "none" without fluid
  std::string velocity_update = "flip";  // "flip" or "apic"
  bool shifting = false;              // particle shifting (a pass over the particles)
  int grid_fields = 1;                // velocity fields (contact: one per body)
  bool operator==(const RateFeatures&) const = default;
};

RateFeatures rate_features(const SceneDescription& scene, const RunCost& cost);

// The time of a particle-step with these features relative to one of a deformable particle
// in plain fluid (order 2, FLIP, J at the particle, no shifting, one grid field): a factor
// per feature (the spline order, APIC, the volume smoothing or projection, shifting, each
// further grid field), multiplied.
double relative_cost(const RateFeatures& features);

// A step of incompressible water (method.md §12: the projection and its pressure solve, the
// multigrid) costs this many times the explicit step of the same features. Measured
// 2026-12-03, CPU time on 1 thread, the Lobovsky tank at 4 mm (45,000 particles, APIC,
// shifting, J at the particle): the incompressible scene as shipped 43.6 ms a step over its
// whole run (89.1 s, 2,043 steps; 34.2 ms in bench's first 100), the weakly compressible
// scene with the same features 5.9 ms (bench). Used only where the nearest record is of the
// other model: a record of incompressible water has the solve in its rate.
inline constexpr double kIncompressibleCost = 7.4;

// A particle of a rigid body costs this share of a deformable one (it carries no stress and
// takes its velocity from the body): measured 0.65 in wall time and 0.87 in CPU time with
// half of the 2 mm hydrostatic tank made rigid; incline_block, 86 % rigid, runs faster still.
inline constexpr double kRigidParticleCost = 0.65;

// A frame costs a fixed time (a group in run.h5, the XDMF sidecar, the conservation row)
// and a time per particle (its fields, in id order, written) [s].
inline constexpr double kFrameSeconds = 2.5e-3;
inline constexpr double kFrameSecondsPerParticle = 1.0e-6;

// One measured rate (a `bsmpm bench` run).
struct CalibrationRecord {
  MachineIdentity machine;
  int threads = 1;
  RateFeatures features;
  double particle_steps_per_second = 0.0;
  double particles = 0.0;    // of the benchmarked scene
  double rigid_particles = 0.0;  // of them in rigid bodies
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

// The predicted wall time of a run from a record: its particle-steps at the record's rate,
// scaled from the record's features and rigid share to the run's, and its frames.
struct WallTime {
  double particle_steps_per_second = 0.0;  // the record's rate for this run
  double stepping_seconds = 0.0;
  double frame_seconds = 0.0;
  double seconds = 0.0;                    // the sum
};
WallTime predict_wall_time(const RunCost& cost, const RateFeatures& features, const CalibrationRecord& record);

// "40 s", "12 min", "3.2 h", "5 days": the age of a record.
std::string format_age(double seconds);

}  // namespace bsmpm

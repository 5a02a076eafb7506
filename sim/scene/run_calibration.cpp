#include "scene/run_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/format.hpp"

namespace bsmpm {

RateFeatures rate_features(const SceneDescription& scene, const RunCost& cost) {
  RateFeatures f;
  f.order = scene.order;
  bool fluid = false, elastic = false, incompressible = false;
  for (const BodyDescription& b : scene.bodies) {
    fluid = fluid || is_fluid(b.material);
    elastic = elastic || is_elastic(b.material);
    incompressible = incompressible || is_incompressible(b.material);
  }
  // Incompressible water is a kind of its own: its steps carry the pressure solve.
  const std::string water = incompressible ? "incompressible" : "fluid";
  f.materials = elastic && fluid ? "elastic+" + water : elastic ? "elastic" : fluid ? water : "rigid";
  using FluidVolume = SolverSettings::FluidVolume;
  const FluidVolume volume = scene.solver.fluid_volume;
  f.fluid_volume = !fluid                               ? "none"
                   : volume == FluidVolume::kSmoothed  ? "smoothed"
                   : volume == FluidVolume::kProjected ? "projected"
                                                       : "particle";
  f.velocity_update = scene.solver.velocity_update == SolverSettings::VelocityUpdate::kApic ? "apic" : "flip";
  f.shifting = fluid && scene.solver.shifting > 0.0;
  f.grid_fields = cost.grid_fields;
  return f;
}

std::string calibration_key(const CalibrationRecord& r) {
  const RateFeatures& f = r.features;
  return format("%s|%d|%d|%d|%s|%s|%s|%d|%d", r.machine.cpu.c_str(), r.machine.cores, r.threads, f.order,
                f.materials.c_str(), f.fluid_volume.c_str(), f.velocity_update.c_str(), f.shifting ? 1 : 0,
                f.grid_fields);
}

std::vector<CalibrationRecord> merge_calibration(std::vector<CalibrationRecord> records, const CalibrationRecord& fresh) {
  const std::string key = calibration_key(fresh);
  const auto same = std::find_if(records.begin(), records.end(),
                                 [&](const CalibrationRecord& r) { return calibration_key(r) == key; });
  if (same == records.end()) records.push_back(fresh);
  else if (same->recorded_at <= fresh.recorded_at) *same = fresh;
  return records;
}

namespace {

// How far a record is from the run, and in what.
struct Distance {
  double score = 0.0;
  std::vector<std::string> differences;
};

Distance distance(const CalibrationRecord& r, const MachineIdentity& machine, int threads, const RateFeatures& run) {
  Distance d;
  auto differ = [&](double weight, std::string what) {
    d.score += weight;
    d.differences.push_back(std::move(what));
  };
  if (!(r.machine == machine))
    differ(1000.0, format("measured on another machine (%d x %s)", r.machine.cores, r.machine.cpu.c_str()));
  if (r.threads != threads) differ(100.0 * std::abs(std::log2(double(r.threads) / threads)) + 50.0,
                                   format("%d thread%s, the run's %d", r.threads, r.threads == 1 ? "" : "s", threads));
  const RateFeatures& f = r.features;
  if (f.order != run.order) differ(10.0 * std::abs(f.order - run.order), format("order %d, the run's %d", f.order, run.order));
  if (f.materials != run.materials) differ(10.0, format("%s, the run's %s", f.materials.c_str(), run.materials.c_str()));
  if (f.fluid_volume != run.fluid_volume)
    differ(5.0, format("fluid volume %s, the run's %s", f.fluid_volume.c_str(), run.fluid_volume.c_str()));
  if (f.grid_fields != run.grid_fields)
    differ(5.0, format("%d grid field%s, the run's %d", f.grid_fields, f.grid_fields == 1 ? "" : "s", run.grid_fields));
  if (f.velocity_update != run.velocity_update)
    differ(2.0, format("%s, the run's %s", f.velocity_update.c_str(), run.velocity_update.c_str()));
  if (f.shifting != run.shifting)
    differ(2.0, format("shifting %s, the run's %s", f.shifting ? "on" : "off", run.shifting ? "on" : "off"));
  return d;
}

}  // namespace

std::optional<CalibrationChoice> choose_calibration(const std::vector<CalibrationRecord>& records,
                                                    const MachineIdentity& machine, int threads,
                                                    const RateFeatures& features) {
  std::optional<CalibrationChoice> best;
  double best_score = 0.0;
  for (const CalibrationRecord& r : records) {
    if (!(r.particle_steps_per_second > 0.0)) continue;
    Distance d = distance(r, machine, threads, features);
    if (!best || d.score < best_score || (d.score == best_score && r.recorded_at > best->record->recorded_at)) {
      best = CalibrationChoice{&r, std::move(d.differences)};
      best_score = d.score;
    }
  }
  return best;
}

double relative_cost(const RateFeatures& f) {
  // Measured as CPU time per particle-step of `bsmpm bench` on 1 thread (110 steps less 10,
  // the median of three sittings), one feature changed at a time from plain fluid:
  // lobovsky_h300 at 4 mm (45,000 particles) for the order, the velocity update, the fluid
  // volume and shifting; the hydrostatic tank at 2 mm (40,000) split in two bodies in contact
  // for a second field. The factors multiply: APIC with smoothing measured 1.77 (1.34 x 1.31
  // = 1.76), all three of lobovsky_h300 2.08 (2.23). An elastic particle costs what a fluid
  // one does (0.97-1.03). docs/validation.md, "Predicted wall time".
  const double order = f.order == 1 ? 0.6 : f.order == 3 ? 1.34 : 1.0;
  const double update = f.velocity_update == "apic" ? 1.34 : 1.0;
  const double volume = f.fluid_volume == "smoothed" ? 1.31 : f.fluid_volume == "projected" ? 1.08 : 1.0;
  const double shifting = f.shifting ? 1.27 : 1.0;
  const double fields = std::pow(1.09, std::max(0, f.grid_fields - 1));
  const double projection = f.materials.find("incompressible") != std::string::npos ? kIncompressibleCost : 1.0;
  return order * update * volume * shifting * fields * projection;
}

namespace {

// The work of one step in deformable-particle units.
double work_per_step(double particles, double rigid, const RateFeatures& f) {
  return relative_cost(f) * (particles - rigid + kRigidParticleCost * rigid);
}

}  // namespace

WallTime predict_wall_time(const RunCost& cost, const RateFeatures& features, const CalibrationRecord& record) {
  WallTime w;
  // Work per second this machine did in the record, then the run's work at that pace.
  const double work_rate = record.particle_steps_per_second / record.particles *
                           work_per_step(record.particles, record.rigid_particles, record.features);
  const double work = cost.steps * work_per_step(cost.particles, cost.rigid_particles, features);
  w.stepping_seconds = work / work_rate;
  w.particle_steps_per_second = cost.particle_steps / w.stepping_seconds;
  w.frame_seconds = cost.frames * (kFrameSeconds + kFrameSecondsPerParticle * cost.particles);
  w.seconds = w.stepping_seconds + w.frame_seconds;
  return w;
}

std::string format_age(double s) {
  s = std::max(s, 0.0);
  if (s < 90.0) return format("%.0f s", s);
  if (s < 90.0 * 60.0) return format("%.0f min", s / 60.0);
  if (s < 48.0 * 3600.0) return format("%.2g h", s / 3600.0);
  return format("%.0f days", s / 86400.0);
}

}  // namespace bsmpm

#include "scene/run_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/format.hpp"

namespace bsmpm {

RateFeatures rate_features(const SceneDescription& scene, const RunCost& cost) {
  RateFeatures f;
  f.order = scene.order;
  bool fluid = false, elastic = false;
  for (const BodyDescription& b : scene.bodies) {
    fluid = fluid || is_fluid(b.material);
    elastic = elastic || std::holds_alternative<ElasticSolid>(b.material);
  }
  f.materials = elastic && fluid ? "elastic+fluid" : elastic ? "elastic" : fluid ? "fluid" : "rigid";
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

double predicted_wall_seconds(const RunCost& cost, const CalibrationRecord& record) {
  return cost.particle_steps / record.particle_steps_per_second;
}

std::string format_age(double s) {
  s = std::max(s, 0.0);
  if (s < 90.0) return format("%.0f s", s);
  if (s < 90.0 * 60.0) return format("%.0f min", s / 60.0);
  if (s < 48.0 * 3600.0) return format("%.2g h", s / 3600.0);
  return format("%.0f days", s / 86400.0);
}

}  // namespace bsmpm

#include "study/run_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "io/run_summary.hpp"

namespace bsmpm {

namespace {

using Type = MetricSpec::Type;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Indices of the samples inside the metric's window (all when it has none).
std::vector<std::size_t> in_window(const Series& s, const MetricSpec& m, double time_factor) {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  if (m.time) lo = (*m.time)[0], hi = (*m.time)[1];
  if (m.time_star) lo = (*m.time_star)[0] / time_factor, hi = (*m.time_star)[1] / time_factor;
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < s.t.size(); ++k)
    if (s.t[k] >= lo && s.t[k] <= hi) out.push_back(k);
  return out;
}

struct Event {
  double value = kNaN, time = kNaN;
};

Event extreme(const Series& s, const std::vector<std::size_t>& window, bool largest) {
  Event e;
  for (std::size_t k : window)
    if (std::isnan(e.value) || (largest ? s.y[k] > e.value : s.y[k] < e.value)) e = {s.y[k], s.t[k]};
  return e;
}

Event probe_event(const MetricSpec& m, const Series& raw, double time_factor) {
  switch (m.type) {
    case Type::kPeak:
    case Type::kMean:
    case Type::kImpactTime: {
      const Series f = apply_sensor_model(raw, m.sensor);
      const auto window = in_window(f, m, time_factor);
      if (m.type == Type::kPeak) return extreme(f, window, true);
      if (m.type == Type::kImpactTime) {
        for (std::size_t k : window)
          if (f.y[k] > m.threshold) return {f.t[k], f.t[k]};
        return {};
      }
      if (window.empty()) return {};
      double sum = 0.0;
      for (std::size_t k : window) sum += f.y[k];
      return {sum / window.size(), kNaN};
    }
    case Type::kMinRaw: {
      // The lowest raw sample after first contact: before it a dry sensor reads exactly 0.
      auto window = in_window(raw, m, time_factor);
      const auto contact = std::find_if(window.begin(), window.end(), [&](std::size_t k) { return raw.y[k] > m.threshold; });
      window.erase(window.begin(), contact);
      return extreme(raw, window, false);
    }
    default: {
      const Event e = extreme(raw, in_window(raw, m, time_factor), true);
      return m.type == Type::kTimeOfMax ? Event{e.time, e.time} : e;
    }
  }
}

double summary_value(const MetricSpec& m, const RunSummary& s) {
  switch (m.type) {
    case Type::kWallSeconds: return s.wall_seconds;
    case Type::kSteps: return static_cast<double>(s.steps);
    case Type::kParticles: return static_cast<double>(s.particles);
    case Type::kPeakMemory: return s.peak_memory_mb;
    default: return s.particle_steps_per_second;
  }
}

}  // namespace

Series probe_column(const RunReader& run, const std::string& probe, const std::string& column) {
  const auto names = run.probe_names();
  if (std::find(names.begin(), names.end(), probe) == names.end())
    throw IoError(run.path() + ": no probe \"" + probe + "\"");
  const RunProbeSeries p = run.probe(probe);
  const auto col = std::find(p.columns.begin(), p.columns.end(), column);
  const auto t = std::find(p.columns.begin(), p.columns.end(), "t");
  if (col == p.columns.end() || t == p.columns.end())
    throw IoError(run.path() + ": probe \"" + probe + "\" has no column \"" + column + "\"");
  const std::size_t nc = p.columns.size(), ic = col - p.columns.begin(), it = t - p.columns.begin();
  Series s;
  for (std::size_t r = 0; r < p.rows; ++r) {
    const double time = p.values[r * nc + it];
    // The first sample is taken at t = 0, before any step: it holds over no interval.
    if (!s.t.empty() && !(time > s.t.back())) continue;
    if (r == 0 && time <= 0.0 && p.rows > 1) continue;
    s.t.push_back(time);
    s.y.push_back(p.values[r * nc + ic]);
  }
  return s;
}

MetricValues compute_metrics(const std::string& run_dir, const std::vector<MetricSpec>& metrics) {
  MetricValues out;
  const std::string h5 = (std::filesystem::path(run_dir) / "run.h5").string();
  std::unique_ptr<RunReader> run;
  std::unique_ptr<RunSummary> summary;
  for (const auto& m : metrics) {
    const auto columns = m.columns();
    if (!m.uses_probe()) {
      if (!summary) summary = std::make_unique<RunSummary>(read_run_summary(run_dir));
      out.emplace_back(columns[0], summary_value(m, *summary));
      continue;
    }
    if (!run) run = std::make_unique<RunReader>(h5);
    const double time_factor = run->reference().time_factor();
    const Event e = probe_event(m, probe_column(*run, m.probe, m.column), time_factor);
    out.emplace_back(columns[0], e.value);
    if (columns.size() == 2) out.emplace_back(columns[1], e.value * time_factor);  // a time, in T*
    if (columns.size() == 3) {
      out.emplace_back(columns[1], e.time);
      out.emplace_back(columns[2], e.time * time_factor);
    }
  }
  return out;
}

}  // namespace bsmpm

// A study as plain, validated data: one base scene, the axes whose Cartesian product gives
// the cases, what to measure in each run and which plots to draw (docs/studies.md).
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "probes/sensor_model.hpp"

namespace bsmpm {

// One scene override, "key=value" on the command line of bsmpm run, with where the study
// file says it (errors about it name that place).
struct Assignment {
  std::string key;
  std::string value;  // TOML text
  SourceLocation where;
  std::string text() const { return key + "=" + value; }
};

struct AxisValue {
  std::string label;
  double coordinate = std::nan("");  // where it sits on a plot's x axis; NaN: not a number
  std::vector<Assignment> assignments;
  SourceLocation where;
};

struct Axis {
  std::string name;
  std::string key;   // the scene key its bare values set; empty for tables of keys
  std::string unit;
  std::vector<AxisValue> values;
  SourceLocation where;
};

// What to extract from a run (docs/studies.md, "Metrics").
struct MetricSpec {
  enum class Type {
    kPeak, kMean, kMinRaw, kImpactTime, kMax, kTimeOfMax,                        // from a probe
    kWallSeconds, kSteps, kParticles, kPeakMemory, kParticleStepsPerSecond       // from summary.json
  };
  std::string name;
  Type type = Type::kPeak;
  std::string probe;
  std::string column;
  std::optional<std::array<double, 2>> time;       // window [s]
  std::optional<std::array<double, 2>> time_star;  // window [T*]
  double threshold = 0.0;
  SensorModel sensor;
  SourceLocation where;
  SourceLocation probe_where;

  bool uses_probe() const { return type <= Type::kTimeOfMax; }
  // The CSV columns it yields: the value, then the time of the event where it has one.
  std::vector<std::string> columns() const;
};

const std::vector<std::string>& metric_type_names();  // in the order of MetricSpec::Type

// A measured or published series drawn under a series plot, filtered like the simulation.
struct ReferenceSeries {
  std::string path;   // absolute; two columns: T*, value
  std::string probe;  // the panel it belongs to
  std::string label;
  double length = 0.0;  // H of its T* [m]
};

struct PlotSpec {
  std::string name;
  std::string type = "metric";  // "metric", "profile" or "series"
  std::string title, xlabel, ylabel;
  std::string x;                        // metric: an axis; series: "t" or "T*"
  std::vector<std::string> y;           // metric and profile: metric names
  std::vector<double> positions;        // profile: x of each metric
  std::vector<std::string> probes;      // series
  std::string column;                   // series
  std::string fit;                      // "", "parabola", "exponential", "decaying_exponential"
  bool fit_offset = true;               // exponential: a exp(b x) + c, or a exp(b x)
  std::vector<ReferenceSeries> references;
};

struct StudyDescription {
  std::string path;        // the study file
  std::string name;
  std::string title;
  std::string scene_path;  // the base scene, resolved against the study file's folder
  std::string scene_text;  // its text as read
  int threads = 1;         // per case
  std::vector<Assignment> defaults;
  SensorModel sensor;
  std::vector<Axis> axes;
  std::vector<MetricSpec> metrics;
  std::vector<PlotSpec> plots;

  std::size_t case_count() const;
};

}  // namespace bsmpm

// The metrics of one finished run (docs/studies.md, "Metrics"): probe series read from
// DIR/run.h5 and filtered by the sensor model, costs read from DIR/summary.json.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/run_reader.hpp"
#include "probes/sensor_model.hpp"
#include "study/study_description.hpp"

namespace bsmpm {

// (column, value) in the order of MetricSpec::columns(); NaN where the window held nothing.
using MetricValues = std::vector<std::pair<std::string, double>>;

MetricValues compute_metrics(const std::string& run_dir, const std::vector<MetricSpec>& metrics);

// One column of a probe against time [s]; throws IoError when the probe or column is absent.
Series probe_column(const RunReader& run, const std::string& probe, const std::string& column);

}  // namespace bsmpm

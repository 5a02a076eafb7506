// The parts of the study loader, one file each: the [[metrics]] and the [[plots]] tables.
#pragma once

#include <string>
#include <vector>

#include "parameters/table_reader.hpp"
#include "study/study_description.hpp"

namespace bsmpm {

// Names that become CSV columns and Python identifiers.
bool is_identifier(const std::string& name);

MetricSpec read_metric(TableReader& t, const SensorModel& defaults);
PlotSpec read_plot(TableReader& t, const StudyDescription& study, const std::string& study_dir);

}  // namespace bsmpm

// OUT/plan.json: a validated study expanded into its cases, for the Snakemake workflow
// (scripts/workflow/Snakefile) and the scripts that aggregate and plot (docs/studies.md).
#pragma once

#include <string>
#include <vector>

#include "study/study_cases.hpp"

namespace bsmpm {

struct PlanContext {
  std::string program;   // absolute path of the bsmpm executable the cases run
  std::string version;   // its `bsmpm --version` line
};

std::string plan_json(const StudyDescription& study, const std::vector<StudyCase>& cases, const PlanContext& context);

// Identifies the metrics' definitions: a case's metrics.json made under other definitions is
// extracted again from its run (the run itself is kept).
std::string metrics_hash(const StudyDescription& study);

// Writes `text` to `path` unless the file holds it already (its time stamp then stays, and
// Snakemake sees nothing new); returns whether it wrote.
bool write_if_changed(const std::string& path, const std::string& text);

}  // namespace bsmpm

// Changes to a study from the command line, for trying it out before its real runs: more
// default overrides (--set KEY=VALUE, before the axes' values) and other values for a keyed
// axis (--axis NAME=V1,V2,...). They change the cases' keys like any other override.
#pragma once

#include <string>
#include <vector>

#include "study/study_description.hpp"

namespace bsmpm {

// Throws UsageError on a malformed option or an axis that is unknown or has no key.
void apply_study_options(StudyDescription& study, const std::vector<std::string>& sets,
                         const std::vector<std::string>& axes);

}  // namespace bsmpm

// Changes to a study from the command line, for trying it out before its real runs: more
// default overrides (--set KEY=VALUE, before the axes' values), other values for a keyed
// axis (--axis NAME=V1,V2,...), and some of the values of an axis of tables, by label
// (--axis setting=shipped,APIC). Values of their own change the cases' keys like any other
// override; values chosen by label keep theirs.
#pragma once

#include <string>
#include <vector>

#include "study/study_description.hpp"

namespace bsmpm {

// Throws UsageError on a malformed option, an unknown axis or a label an axis does not have.
void apply_study_options(StudyDescription& study, const std::vector<std::string>& sets,
                         const std::vector<std::string>& axes);

}  // namespace bsmpm

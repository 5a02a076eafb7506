// The cases of a study: the Cartesian product of its axes (the last axis varies fastest),
// each the base scene with the study's default overrides and one value of every axis.
#pragma once

#include <string>
#include <vector>

#include "scene/scene_loader.hpp"
#include "study/study_description.hpp"

namespace bsmpm {

struct StudyCase {
  std::string key;                      // names its directory: cases/<key>
  std::vector<std::size_t> value_index;  // per axis
  std::vector<Assignment> assignments;  // the defaults, then each axis's, in axis order
  std::vector<std::string> overrides() const;  // as --set arguments, "key=value"
};

// Every case, keyed by a hash of the base scene's text, its overrides and `version` (the
// program's): the same case of another study, or of the same study rerun, finds its run.
std::vector<StudyCase> expand_cases(const StudyDescription& study, const std::string& version);

// Loads the base scene with each case's overrides (loading rejects unknown keys and values
// out of range) and checks that the metrics' and plots' probes and columns exist. Errors
// are re-thrown naming the study file's line of the value at fault.
void validate_cases(const StudyDescription& study, const std::vector<StudyCase>& cases,
                    const std::vector<SceneExtension>& extensions = {});

// "H = 300 mm, grid = 0.01": the case's axis labels.
std::string describe_case(const StudyDescription& study, const StudyCase& c);

// 64-bit FNV-1a as 16 hex digits.
std::string hash_text(const std::string& text);

}  // namespace bsmpm

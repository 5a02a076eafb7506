// Study file (TOML) -> validated StudyDescription, with the scene's TableReader: every
// unknown key, wrong type or value out of range is a SceneError naming file:line:column and
// the dotted key. What depends on the base scene (do the overridden keys exist, do the
// probes) is checked when the cases are expanded (study_cases.hpp).
#pragma once

#include <string>

#include "study/study_description.hpp"

namespace bsmpm {

StudyDescription load_study(const std::string& path);

// The same from text in memory; `path` names it in messages and anchors relative paths.
StudyDescription load_study_text(const std::string& text, const std::string& path);

}  // namespace bsmpm

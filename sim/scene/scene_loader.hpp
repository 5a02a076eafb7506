// TOML scene file -> validated SceneDescription (stage one and two of pbrt-v4's loading).
#pragma once

#include <string>
#include <vector>

#include "scene/scene_description.hpp"

namespace bsmpm {

// Reads, overrides and validates a scene; throws SceneError (file:line:column, key) on the
// first problem, IoError when the file cannot be read, UsageError on a malformed --set.
SceneDescription load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same from text in memory; `path` names it in messages.
SceneDescription load_scene_text(const std::string& text, const std::string& path,
                                 const std::vector<std::string>& overrides = {});

}  // namespace bsmpm

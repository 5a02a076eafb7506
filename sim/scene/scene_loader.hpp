// TOML scene file -> validated SceneDescription (stage one and two of pbrt-v4's loading).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "scene/scene_description.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

// A top-level table that another part of the program owns (e.g. [render], validated by the
// renderer): the loader hands it to `validate`, which must read every key it accepts and
// call finish(). The solver itself never looks inside; without a registered validator the
// loader passes such a table over (the program always registers it).
struct SceneExtension {
  std::string table;
  std::function<void(TableReader&)> validate;
};

// Reads, overrides and validates a scene; throws SceneError (file:line:column, key) on the
// first problem, IoError when the file cannot be read, UsageError on a malformed --set.
SceneDescription load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                            const std::vector<SceneExtension>& extensions = {});

// Same from text in memory; `path` names it in messages.
SceneDescription load_scene_text(const std::string& text, const std::string& path,
                                 const std::vector<std::string>& overrides = {},
                                 const std::vector<SceneExtension>& extensions = {});

}  // namespace bsmpm

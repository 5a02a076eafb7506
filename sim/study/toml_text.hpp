// A TOML value written back as TOML text, short and exact: the VALUE of a --set KEY=VALUE.
// (toml++'s own formatter prints 0.3 as 0.29999999999999999 and strings in single quotes.)
#pragma once

#include <string>

#include <toml++/toml.h>

namespace bsmpm {

// Throws SceneError at the node for values --set cannot carry (dates and times).
std::string toml_value_text(const toml::node& node);

}  // namespace bsmpm

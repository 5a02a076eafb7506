// Command-line overrides of scene values: --set grid.cell_size=0.008, --set
// bodies[0].velocity=[1.0, 0.0], --set materials.water.equation_of_state=linear.
// A value is read as TOML; a bare word that is not valid TOML is taken as a string.
#pragma once

#include <string_view>

#include <toml++/toml.h>

namespace bsmpm {

// Applies one KEY=VALUE assignment to the scene table; throws UsageError when malformed.
void apply_override(toml::table& root, std::string_view assignment);

}  // namespace bsmpm

// Published colour-map tables (definitions in <name>_table.cpp, with their sources).
#pragma once

#include <array>

namespace bsmpm::render {

extern const std::array<std::array<double, 3>, 256> kViridisTable;
extern const std::array<std::array<double, 3>, 256> kInfernoTable;

}  // namespace bsmpm::render

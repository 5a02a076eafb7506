// Keys several materials share, read one way by all of them.
#pragma once

#include "parameters/table_reader.hpp"

namespace bsmpm {

// density = rho0 [kg/m3], required, > 0 (every deformable material's).
inline double read_density(TableReader& t) { return t.number("density", Range::positive()); }

// viscosity = mu [Pa s], >= 0; absent: 0 (inviscid). The fluids'.
inline double read_viscosity(TableReader& t) { return t.number_or("viscosity", 0.0, Range::non_negative()); }

}  // namespace bsmpm

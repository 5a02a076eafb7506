// The quantities a figure colours particles by. Water: pressure, P* = P/(rho g H) with the
// run's reference scales, or speed |v|. Solids (elastic or rigid bodies): displacement
// magnitude |x - X|. Values are in SI units; colour bars show them in display units.
#pragma once

#include <string>
#include <vector>

#include "io/run_reader.hpp"

namespace bsmpm::render {

enum class Field { kPressure, kPStar, kVelocity, kDisplacement };

struct FieldInfo {
  std::string key;       // as named on the command line and in [render]: "pressure"
  std::string quantity;  // for the colour bar: "pressure"
  std::string unit;      // display unit: "kPa"; empty when dimensionless
  double display_scale;  // display value = SI value * display_scale
};

const FieldInfo& field_info(Field field);

// The fields water can be coloured by: "pressure", "pstar", "velocity".
const std::vector<std::string>& water_field_names();
// Throws UsageError for an unknown name, listing the known ones.
Field water_field_named(const std::string& name);

// The field's value for every particle of frame `frame`, in id order, SI units.
std::vector<double> field_values(const RunReader& run, int frame, Field field);

}  // namespace bsmpm::render

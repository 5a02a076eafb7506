#include "figure/field.hpp"

#include "core/error.hpp"

namespace bsmpm::render {

const FieldInfo& field_info(Field field) {
  static const FieldInfo pressure{"pressure", "pressure", "kPa", 1e-3};
  static const FieldInfo pstar{"pstar", "P* = P/(\u03c1gH)", "", 1.0};
  static const FieldInfo velocity{"velocity", "speed", "m/s", 1.0};
  static const FieldInfo displacement{"displacement", "displacement", "mm", 1e3};
  switch (field) {
    case Field::kPressure: return pressure;
    case Field::kPStar: return pstar;
    case Field::kVelocity: return velocity;
    case Field::kDisplacement: break;
  }
  return displacement;
}

const std::vector<std::string>& water_field_names() {
  static const std::vector<std::string> names = {"pressure", "pstar", "velocity"};
  return names;
}

Field water_field_named(const std::string& name) {
  if (name == "pressure") return Field::kPressure;
  if (name == "pstar") return Field::kPStar;
  if (name == "velocity") return Field::kVelocity;
  throw UsageError("unknown field '" + name + "' (known: pressure, pstar, velocity)");
}

std::vector<double> field_values(const RunReader& run, int frame, Field field) {
  switch (field) {
    case Field::kPressure: return run.pressure(frame);
    case Field::kPStar: {
      std::vector<double> p = run.pressure(frame);
      const double scale = run.reference().pressure_scale();
      for (double& v : p) v /= scale;
      return p;
    }
    case Field::kVelocity:
    case Field::kDisplacement: {
      const std::vector<Vec2> v = field == Field::kVelocity ? run.velocity(frame) : run.displacement(frame);
      std::vector<double> out(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) out[k] = v[k].norm();
      return out;
    }
  }
  return {};
}

}  // namespace bsmpm::render

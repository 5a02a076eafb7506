// Weakly compressible Newtonian fluid (docs/method.md §4): sigma = -p I + 2 mu dev(D),
// with a linear or Tait equation of state. K = rho0 c0^2 is the bulk stiffness.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "core/format.hpp"
#include "core/types.hpp"
#include "materials/material_attribute.hpp"
#include "materials/material_keys.hpp"
#include "materials/newtonian_viscosity.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

enum class EquationOfState { kLinear, kTait };

// [materials.NAME] type = "fluid", density, bulk_modulus or sound_speed (exactly one),
// viscosity = 0, equation_of_state = "tait" | "linear", tait_gamma = 7 (in (1, 20]),
// min_pressure (<= 0; absent: no tension cut-off).
struct WeaklyCompressibleFluid {
  static constexpr const char* kType = "fluid";
  static constexpr MaterialKind kKind = MaterialKind::kFluid;

  double density = 1000.0;        // rho0 [kg/m3]
  double bulk_modulus = 1.0e6;    // K [Pa]
  double viscosity = 0.0;         // mu [Pa s]
  EquationOfState eos = EquationOfState::kTait;
  double tait_gamma = 7.0;
  std::optional<double> min_pressure;  // tension cut-off [Pa]; absent: the fluid takes tension (the paper's law)

  static WeaklyCompressibleFluid read(TableReader& t) {
    WeaklyCompressibleFluid f;
    f.density = read_density(t);
    if (t.has("bulk_modulus") == t.has("sound_speed"))
      t.fail(t.has("bulk_modulus") ? "sound_speed" : "bulk_modulus",
             "give exactly one of bulk_modulus [Pa] and sound_speed [m/s]");
    if (t.has("bulk_modulus")) f.bulk_modulus = t.number("bulk_modulus", Range::positive());
    else {
      const double c = t.number("sound_speed", Range::positive());
      f.bulk_modulus = f.density * c * c;
    }
    f.viscosity = read_viscosity(t);
    f.eos = t.choice_or("equation_of_state", "tait", {"tait", "linear"}) == "tait" ? EquationOfState::kTait
                                                                                   : EquationOfState::kLinear;
    if (f.eos == EquationOfState::kTait)
      f.tait_gamma = t.number_or("tait_gamma", 7.0, Range{Bound::exclusive(1.0), Bound::inclusive(20.0)});
    if (t.has("min_pressure")) f.min_pressure = t.number("min_pressure", Range::non_positive());
    return f;
  }

  // p(J) with rho / rho0 = 1 / J.
  double pressure(double J) const {
    const double ratio = 1.0 / J;
    double p;
    if (eos == EquationOfState::kLinear) {
      p = bulk_modulus * (ratio - 1.0);
    } else {
      p = bulk_modulus / tait_gamma * (tait_power(ratio) - 1.0);
    }
    return min_pressure && p < *min_pressure ? *min_pressure : p;
  }

  // (rho/rho0)^gamma; gamma = 7 (water) by multiplication, which is several times faster
  // than std::pow and exact to round-off.
  double tait_power(double ratio) const {
    if (tait_gamma == 7.0) {
      const double r2 = ratio * ratio, r3 = r2 * ratio;
      return r3 * r3 * ratio;
    }
    return std::pow(ratio, tait_gamma);
  }

  // The largest J a particle keeps (method.md §4): J(min_pressure) with a cut-off, else none.
  std::optional<double> largest_volume_ratio() const {
    if (!min_pressure) return std::nullopt;
    return volume_ratio(*min_pressure);
  }

  // Inverse of pressure(): the J at which the fluid carries pressure p.
  double volume_ratio(double p) const {
    if (eos == EquationOfState::kLinear) return 1.0 / (1.0 + p / bulk_modulus);
    return 1.0 / std::pow(1.0 + tait_gamma * p / bulk_modulus, 1.0 / tait_gamma);
  }

  // Energy stored by compression per unit reference volume, w(J) = -int_1^J p(s) ds, so that
  // p = -dw/dJ (the tension cut-off min_pressure is left out):
  //  linear: K (J - 1 - ln J);  Tait: K/g ((J^(1-g) - 1)/(g - 1) + J - 1).
  double stored_energy(double J) const {
    if (eos == EquationOfState::kLinear) return bulk_modulus * (J - 1.0 - std::log(J));
    const double g = tait_gamma;
    return bulk_modulus / g * ((J * tait_power(1.0 / J) - 1.0) / (g - 1.0) + J - 1.0);
  }
  double stored_energy(const Mat2&, double J) const { return stored_energy(J); }

  // c = sqrt(dp/drho).
  double sound_speed(double J) const {
    double c2 = bulk_modulus / density;
    if (eos == EquationOfState::kTait) c2 *= tait_power(1.0 / J) * J;  // (rho/rho0)^(gamma-1)
    return std::sqrt(c2);
  }
  double wave_speed(double J) const { return sound_speed(J); }

  // Fastest signal c + |v| a particle moving at `speed` carries (CFL condition).
  double signal_speed(double J, double speed) const { return sound_speed(J) + speed; }

  // The start-of-run line for a body of this fluid.
  std::string describe(const std::string& body) const {
    const std::string cut_off =
        min_pressure ? format(", tension cut-off p >= %g Pa (J held at %.6g)", *min_pressure, *largest_volume_ratio())
                     : "";
    return format("fluid stress [%s]: %s EOS, K = %g Pa (c0 = %.3g m/s), rho0 = %g kg/m3, %s%s", body.c_str(),
                  eos == EquationOfState::kTait ? "Tait" : "linear", bulk_modulus, sound_speed(1.0), density,
                  describe_viscosity(viscosity).c_str(), cut_off.c_str());
  }

  // What the run file records besides the type and density.
  MaterialAttributes attributes() const {
    return {{"bulk_modulus", bulk_modulus},
            {"viscosity", viscosity},
            {"equation_of_state", std::string(eos == EquationOfState::kTait ? "tait" : "linear")}};
  }

  // Cauchy stress from the pressure and the velocity gradient L.
  template <bool kViscous>
  Mat2 stress(double p, const Mat2& L) const {
    Mat2 sigma = -p * Mat2::Identity();
    if constexpr (kViscous) sigma += newtonian_viscous_stress(viscosity, L);
    return sigma;
  }
};

}  // namespace bsmpm

// Weakly compressible Newtonian fluid (docs/method.md §4): sigma = -p I + 2 mu dev(D),
// with a linear or Tait equation of state. K = rho0 c0^2 is the bulk stiffness.
#pragma once

#include <cmath>

#include "core/types.hpp"

namespace bsmpm {

enum class EquationOfState { kLinear, kTait };

struct WeaklyCompressibleFluid {
  double density = 1000.0;        // rho0 [kg/m3]
  double bulk_modulus = 1.0e6;    // K [Pa]
  double viscosity = 0.0;         // mu [Pa s]
  EquationOfState eos = EquationOfState::kTait;
  double tait_gamma = 7.0;
  double min_pressure = -1.0e300; // tension cut-off [Pa]; -inf keeps tension

  // p(J) with rho / rho0 = 1 / J.
  double pressure(double J) const {
    const double ratio = 1.0 / J;
    double p;
    if (eos == EquationOfState::kLinear) {
      p = bulk_modulus * (ratio - 1.0);
    } else {
      p = bulk_modulus / tait_gamma * (tait_power(ratio) - 1.0);
    }
    return p < min_pressure ? min_pressure : p;
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

  // A tension cut-off is set (the default, -1e300, keeps the paper's law).
  bool has_tension_cut_off() const { return min_pressure > -1e299; }

  // The largest J a particle keeps (method.md §4): J(min_pressure) with a cut-off, else none.
  double largest_volume_ratio() const { return has_tension_cut_off() ? volume_ratio(min_pressure) : 1e300; }

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

  // c = sqrt(dp/drho).
  double sound_speed(double J) const {
    double c2 = bulk_modulus / density;
    if (eos == EquationOfState::kTait) c2 *= tait_power(1.0 / J) * J;  // (rho/rho0)^(gamma-1)
    return std::sqrt(c2);
  }

  // Cauchy stress from the rate of deformation D = sym(L); the deviator is the
  // plane-strain one (D_zz = 0), dev(D) = D - tr(D)/3 I.
  template <bool kViscous>
  Mat2 stress(double p, const Mat2& L) const {
    Mat2 sigma = -p * Mat2::Identity();
    if constexpr (kViscous) {
      const Mat2 D = 0.5 * (L + L.transpose());
      sigma += 2.0 * viscosity * (D - (D.trace() / 3.0) * Mat2::Identity());
    }
    return sigma;
  }
};

}  // namespace bsmpm

// The Newtonian viscous stress 2 mu dev(D) both fluids carry (docs/method.md §4 and §12),
// and its words in the start-of-run summary.
#pragma once

#include <string>

#include "core/format.hpp"
#include "core/types.hpp"

namespace bsmpm {

// 2 mu dev(D) from the velocity gradient L, D = sym(L), with the plane-strain deviator
// (D_zz = 0) dev(D) = D - tr(D)/3 I.
inline Mat2 newtonian_viscous_stress(double mu, const Mat2& L) {
  const Mat2 D = 0.5 * (L + L.transpose());
  return 2.0 * mu * (D - (D.trace() / 3.0) * Mat2::Identity());
}

inline std::string describe_viscosity(double mu) {
  return mu > 0.0 ? format("viscosity %g Pa s", mu) : "inviscid (no viscous term)";
}

}  // namespace bsmpm

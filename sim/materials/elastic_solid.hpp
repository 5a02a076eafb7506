// Elastic solid with large rotations, plane strain (docs/method.md §5; Walhorn 2005 benchmark).
// Two hyperelastic models, both exactly objective and equal to linear elasticity for small
// strains:
//  - Neo-Hookean:               sigma = mu/J (F F^T - I) + lambda ln(J)/J I
//  - Saint Venant-Kirchhoff:    S = lambda tr(E) I + 2 mu E,  sigma = F S F^T / J
#pragma once

#include <cmath>
#include <string>

#include "core/format.hpp"
#include "core/types.hpp"
#include "materials/material_attribute.hpp"
#include "materials/material_keys.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

enum class ElasticModel { kNeoHookean, kSaintVenantKirchhoff };

// [materials.NAME] type = "elastic", density, youngs_modulus, poisson_ratio = 0 (in [0, 0.5)),
// elastic_model = "neo_hookean" | "saint_venant_kirchhoff".
struct ElasticSolid {
  static constexpr const char* kType = "elastic";
  static constexpr MaterialKind kKind = MaterialKind::kElastic;

  double density = 1000.0;  // rho0 [kg/m3]
  double youngs_modulus = 1.0e6;
  double poisson_ratio = 0.0;
  ElasticModel model = ElasticModel::kNeoHookean;

  static ElasticSolid read(TableReader& t) {
    ElasticSolid e;
    e.density = read_density(t);
    e.youngs_modulus = t.number("youngs_modulus", Range::positive());
    e.poisson_ratio = t.number_or("poisson_ratio", 0.0, Range{Bound::inclusive(0.0), Bound::exclusive(0.5)});
    e.model = t.choice_or("elastic_model", "neo_hookean", {"neo_hookean", "saint_venant_kirchhoff"}) == "neo_hookean"
                  ? ElasticModel::kNeoHookean
                  : ElasticModel::kSaintVenantKirchhoff;
    return e;
  }

  double lame_lambda() const {
    const double E = youngs_modulus, nu = poisson_ratio;
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  }
  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }

  // P-wave speed sqrt((lambda + 2 mu) / rho) in the current configuration.
  double wave_speed(double J) const {
    return std::sqrt((lame_lambda() + 2.0 * shear_modulus()) * J / density);
  }

  // Fastest signal c + |v| a particle moving at `speed` carries (CFL condition).
  double signal_speed(double J, double speed) const { return wave_speed(J) + speed; }

  std::string describe(const std::string& body) const {
    return format("elastic stress [%s]: %s, E = %g Pa, nu = %g, rho0 = %g kg/m3", body.c_str(),
                  model == ElasticModel::kNeoHookean ? "Neo-Hookean" : "Saint Venant-Kirchhoff", youngs_modulus,
                  poisson_ratio, density);
  }

  MaterialAttributes attributes() const {
    return {{"youngs_modulus", youngs_modulus}, {"poisson_ratio", poisson_ratio}};
  }

  // Strain energy per unit reference volume, whose derivative gives stress() (plane strain,
  // F_zz = 1): Neo-Hookean mu/2 (tr(F^T F) - 2) - mu ln J + lambda/2 (ln J)^2;
  // Saint Venant-Kirchhoff lambda/2 tr(E)^2 + mu tr(E^2).
  double stored_energy(const Mat2& F) const {
    const double lambda = lame_lambda(), mu = shear_modulus();
    if (model == ElasticModel::kNeoHookean) {
      const double lnJ = std::log(F.determinant());
      return 0.5 * mu * (F.squaredNorm() - 2.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
    }
    const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
    return 0.5 * lambda * E.trace() * E.trace() + mu * E.squaredNorm();
  }
  double stored_energy(const Mat2& F, double) const { return stored_energy(F); }

  Mat2 stress(const Mat2& F) const {
    const double J = F.determinant();
    const double lambda = lame_lambda(), mu = shear_modulus();
    const Mat2 I = Mat2::Identity();
    if (model == ElasticModel::kNeoHookean) {
      return (mu / J) * (F * F.transpose() - I) + (lambda * std::log(J) / J) * I;
    }
    const Mat2 E = 0.5 * (F.transpose() * F - I);
    const Mat2 S = lambda * E.trace() * I + 2.0 * mu * E;
    return F * S * F.transpose() / J;
  }
};

}  // namespace bsmpm

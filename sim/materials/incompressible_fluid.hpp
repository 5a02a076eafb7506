// Incompressible Newtonian fluid (docs/method.md §12): sigma = -p I + 2 mu dev(D), where p is
// no material law but the Lagrange multiplier of div v = 0, found each step by the pressure
// projection (step/incompressible/). The material holds what the particles need: the
// density and the viscous stress, which the step integrates explicitly (the predictor).
#pragma once

#include <string>

#include "core/format.hpp"
#include "core/types.hpp"
#include "materials/material_attribute.hpp"
#include "materials/material_keys.hpp"
#include "materials/newtonian_viscosity.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

// [materials.NAME] type = "incompressible_fluid", density, viscosity = 0.
struct IncompressibleFluid {
  static constexpr const char* kType = "incompressible_fluid";
  static constexpr MaterialKind kKind = MaterialKind::kFluid;

  double density = 1000.0;  // rho0 [kg/m3]
  double viscosity = 0.0;   // mu [Pa s]

  static IncompressibleFluid read(TableReader& t) {
    IncompressibleFluid f;
    f.density = read_density(t);
    f.viscosity = read_viscosity(t);
    return f;
  }

  // No sound: the flow's speed alone bounds the step (the viscous limit is the step's, which
  // knows the cell size: viscous_speed).
  double wave_speed(double) const { return 0.0; }
  double signal_speed(double, double speed) const { return speed; }
  double stored_energy(const Mat2&, double) const { return 0.0; }  // p does no work on div v = 0

  // The largest step explicit viscosity allows on cells of size h, h^2 rho0 / (4 mu) (2-D
  // diffusion, docs/method.md §12), as the speed h / dt that the CFL step divides by.
  double viscous_speed(double h) const { return 4.0 * viscosity / (density * h); }

  // The viscous (deviatoric) Cauchy stress from the velocity gradient: 2 mu dev(D), with the
  // plane-strain deviator dev(D) = D - tr(D)/3 I (as the weakly compressible fluid's).
  Mat2 viscous_stress(const Mat2& L) const { return newtonian_viscous_stress(viscosity, L); }

  std::string describe(const std::string& body) const {
    return format("fluid stress [%s]: incompressible (pressure from the projection), rho0 = %g kg/m3, %s",
                  body.c_str(), density, describe_viscosity(viscosity).c_str());
  }
  MaterialAttributes attributes() const {
    return {{"viscosity", viscosity}, {"model", std::string("incompressible")}};
  }
};

}  // namespace bsmpm

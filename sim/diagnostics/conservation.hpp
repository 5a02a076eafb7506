// Conservation and energy of a run at one instant (docs/output-format.md, "conservation"):
// mass, momentum, kinetic, gravitational and stored elastic energy of the deformable
// bodies, and the work done on them since t = 0 by gravity and by the essential conditions
// (walls, clamps, contact; recorded by the step, StepDiagnostics). Rigid bodies move as
// prescribed and are left out: what they do to the others is work from outside.
#pragma once

#include <string>
#include <vector>

#include "core/types.hpp"
#include "step/simulation.hpp"

namespace bsmpm {

struct ConservationTotals {
  double time = 0.0;
  long step = 0;
  double mass = 0.0;                 // kg/m
  Vec2 momentum = Vec2::Zero();      // kg m/s per m
  double kinetic = 0.0;              // sum m |v|^2 / 2 [J/m]
  double gravitational = 0.0;        // -sum m g . x (zero at the origin) [J/m]
  double elastic = 0.0;              // sum V0 w(J or F): compression of fluids, strain of solids [J/m]
  double work_gravity = 0.0;         // sum m g . (x - x0): the drop of the gravitational energy [J/m]
  ConstraintWork work;               // walls, clamps, contact since t = 0 [J/m]

  double total() const { return kinetic + gravitational + elastic; }
};

// Sums over the particles in slot order (serially: the same bits for any thread count).
ConservationTotals measure_conservation(const Simulation& sim, const Vec2& gravity);

// The columns of the conservation series, and one row of it.
const std::vector<std::string>& conservation_columns();
const std::vector<std::string>& conservation_units();  // per column, SI per metre of depth
std::vector<double> conservation_row(const ConservationTotals& c);

}  // namespace bsmpm

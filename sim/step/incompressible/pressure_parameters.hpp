// [solver.pressure]: the incompressible fluid's pressure projection (docs/method.md §12).
// Read when a body is of an "incompressible_fluid" material; the table is an error without one.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/boundaries.hpp"
#include "step/effects/scene_tables.hpp"

namespace bsmpm {

// The conjugate-gradient solve's preconditioner (docs/method.md §12, "The solve").
enum class PressurePreconditioner { kIncompleteCholesky, kMultigrid };

struct PressureParameters {
  // What J_p, the particles' volume ratio in the quadrature (eq. I2) and the volume error
  // (eq. I3), measures (method.md §12, "What J measures", eq. I5): the projected increment
  // carried from step to step, or the hats' fill by the particles, set each step.
  enum class VolumeMeasure { kIncrement, kFill };
  double tolerance = 1e-6;         // relative residual |b - A p| / |b| of the solve
  int max_iterations = 500;        // beyond: the run stops as unstable
  double volume_correction = 0.5;  // beta: share of the water's excess volume removed per step (eq. I3)
  int volume_correction_filter = 0;  // passes of the [1 2 1] / 4 filter of that excess (eq. I3f; 0: none)
  double stabilization = 0.05;     // alpha of the checkerboard term S (eq. I4)
  double surface_fraction = 0.1;   // a vertex whose hat is filled to less than this carries p = 0
  VolumeMeasure volume_measure = VolumeMeasure::kIncrement;
  // Of the CG solve; incomplete Cholesky by default: multigrid's solution differs within the
  // tolerance, and the flows amplify that beyond it (docs/method.md §12, "The solve").
  PressurePreconditioner preconditioner = PressurePreconditioner::kIncompleteCholesky;
  double density = 1000.0;         // rho0 of the incompressible fluid
  std::array<WallKind, 4> walls{WallKind::kSlip, WallKind::kSlip, WallKind::kSlip, WallKind::kSlip};

  static std::optional<PressureParameters> read(SceneTables& scene) {
    int fluid = -1;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      if (is_incompressible(scene.bodies[b].material)) {
        fluid = static_cast<int>(b);
        break;
      }
    if (fluid < 0) {
      if (scene.solver && scene.solver->has("pressure"))
        scene.solver->fail("pressure", "applies to an incompressible fluid: no body is of a material with "
                                       "type = \"incompressible_fluid\"");
      return std::nullopt;
    }
    PressureParameters p;
    p.density = density_of(scene.bodies[fluid].material);
    // The pressure is not coupled to an elastic body through the contact yet, and one grid
    // cannot step a weakly compressible fluid's sound and an incompressible one's flow.
    for (const BodyTable& b : scene.bodies) {
      if (is_elastic(b.material))
        b.table.fail("material", "an elastic body cannot share a scene with an incompressible fluid (body \"" +
                                     scene.bodies[fluid].name +
                                     "\"): the pressure is not coupled through the contact yet; use a "
                                     "weakly compressible fluid (type = \"fluid\")");
      if (std::holds_alternative<WeaklyCompressibleFluid>(b.material))
        b.table.fail("material", "a weakly compressible fluid cannot share a scene with an incompressible one (body \"" +
                                     scene.bodies[fluid].name + "\")");
    }
    if (scene.solver) {
      if (auto t = scene.solver->optional_table("pressure")) {
        p.tolerance = t->number_or("tolerance", p.tolerance, Range{Bound::exclusive(0.0), Bound::inclusive(0.1)});
        p.max_iterations = static_cast<int>(t->integer_or("max_iterations", p.max_iterations, 1, 100000));
        p.volume_correction = t->number_or("volume_correction", p.volume_correction, Range::closed(0.0, 1.0));
        p.volume_correction_filter =
            static_cast<int>(t->integer_or("volume_correction_filter", p.volume_correction_filter, 0, 16));
        p.stabilization = t->number_or("stabilization", p.stabilization, Range::closed(0.0, 10.0));
        if (t->choice_or("volume_measure", "increment", {"increment", "fill"}) == "fill")
          p.volume_measure = VolumeMeasure::kFill;
        p.surface_fraction = t->number_or("surface_fraction", p.surface_fraction, Range{Bound::exclusive(0.0), Bound::exclusive(1.0)});
        const bool ic = p.preconditioner == PressurePreconditioner::kIncompleteCholesky;
        p.preconditioner = t->choice_or("preconditioner", ic ? "incomplete_cholesky" : "multigrid",
                                        {"incomplete_cholesky", "multigrid"}) == "multigrid"
                               ? PressurePreconditioner::kMultigrid
                               : PressurePreconditioner::kIncompleteCholesky;
        t->finish();
      }
    }
    // The walls' kinds decide which velocity components the projection leaves alone; the
    // tank walls effect owns (and checks) the keys.
    if (auto walls = scene.domain.optional_table("walls"))
      for (int side = 0; side < 4; ++side) {
        const std::string kind = walls->string_or(wall_side_name(side), "slip");
        p.walls[side] = kind == "no_slip" ? WallKind::kNoSlip : kind == "symmetry" ? WallKind::kSymmetry : WallKind::kSlip;
      }
    return p;
  }
};

}  // namespace bsmpm

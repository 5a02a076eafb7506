// Everything one BSMPM step reads and writes, shared by the step and by the effects.
#pragma once

#include <vector>

#include "bspline/clamped_bspline.hpp"
#include "grid/grid.hpp"
#include "particles/body.hpp"
#include "particles/particles.hpp"
#include "step/phase_timer.hpp"
#include "step/simulation.hpp"
#include "step/passes/strip_schedule.hpp"

namespace bsmpm {

// The 1-D basis values and derivatives of one particle, per axis, at x_p^k: computed once
// per step and reused by P2G, G2P, the remap and the velocity gradient.
template <int P>
struct ParticleWeights {
  using Weights = typename ClampedBSpline<P>::Weights;
  int i0 = 0, j0 = 0;  // first control point in x and y
  Weights wx, wy, gx, gy;
};

template <int P>
struct StepState {
  Grid<P> grid;
  Particles particles;
  std::vector<Body> bodies;
  std::vector<GridLayer> layers;
  std::vector<ParticleWeights<P>> weights;
  std::vector<StripSchedule> schedules;    // per body: conflict-free scatter order
  std::vector<std::uint32_t> index_of_id;  // particle id -> current slot
  StepDiagnostics diagnostics;             // what the last step did (contact, ...)
  double time = 0.0;
  double dt = 0.0;
  long step = 0;
  double mass_cutoff = 0.0;  // nodes lighter than this carry no velocity
  PhaseTimer* timer = nullptr;  // wall time per phase: set by bsmpm bench only, else null
};

// Loops over the control points of a box.
template <class F>
inline void for_each_node(const NodeBox& box, int ny, F&& f) {
  for (int i = box.i0; i < box.i1; ++i)
    for (int j = box.j0; j < box.j1; ++j) f(i * ny + j, i, j);
}

// The same, columns shared among the threads: for f that touches only its own control point.
template <class F>
inline void for_each_node_parallel(const NodeBox& box, int ny, F&& f) {
#pragma omp parallel for schedule(static) if ((box.i1 - box.i0) * (box.j1 - box.j0) > 4096)
  for (int i = box.i0; i < box.i1; ++i)
    for (int j = box.j0; j < box.j1; ++j) f(i * ny + j, i, j);
}

}  // namespace bsmpm

// Steps 4, 5 and 7 of docs/method.md §2: the nodal velocities from momentum and force, the
// essential conditions (walls, clamps, contact: the effects' constrain_velocity hooks, given
// here as `constrain`), and the remapped velocities of eq. 13.
#pragma once

#include "step/effect.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

// Calls heavy(layer, n, m) for every active node n of every layer whose mass m is above the
// mass cut-off, and light(layer, n) for the others (the nodes the step leaves at rest).
template <int P, class Heavy, class Light>
void for_each_node_by_mass(StepState<P>& st, Heavy&& heavy, Light&& light) {
  const int ny = st.grid.ny();
  const double cut = st.mass_cutoff;
  for (auto& layer : st.layers)
    for_each_node_parallel(layer.active, ny, [&](int n, int, int) {
      const double m = layer.mass[n];
      if (m > cut) heavy(layer, n, m);
      else light(layer, n);
    });
}

// v_I^k = p_I / m_I, v_I^{k+1} = v_I^k + dt f_I / m_I (eqs. 9-10) for nodes heavier than the
// mass cut-off, then the essential conditions; the FLIP increment then sees the constrained
// velocity: a_I = (v_I^{k+1} - v_I^k) / dt (docs/method.md §2, step 5).
template <int P, class Constrain>
void update_grid_velocity(StepState<P>& st, double dt, Constrain&& constrain) {
  const PhaseScope timed(st.timer, StepPhase::kGridUpdate);
  for_each_node_by_mass(
      st,
      [&](GridLayer& layer, int n, double m) {
        const Vec2 v = layer.momentum[n] / m;                // v_I^k, eq. 6
        layer.velocity[n] = v + (dt / m) * layer.force[n];  // eqs. 9-10
      },
      [](GridLayer&, int) {});
  constrain(VelocityPhase::kUpdate);
  for_each_node_by_mass(
      st,
      [](GridLayer& layer, int n, double m) {
        layer.velocity_increment[n] = layer.velocity[n] - layer.momentum[n] / m;
      },
      [](GridLayer& layer, int n) { layer.velocity[n].setZero(); });
}

// The remapped velocity v_bar_I = sum_p S_Ip m_p v_p / m_I (eq. 13), then the essential
// conditions again: the strain increment (eq. 14) is taken from it.
template <int P, class Constrain>
void update_remap_velocity(StepState<P>& st, Constrain&& constrain) {
  const PhaseScope timed(st.timer, StepPhase::kGridUpdate);
  for_each_node_by_mass(
      st, [](GridLayer& layer, int n, double m) { layer.remap_velocity[n] /= m; },  // eq. 13
      [](GridLayer& layer, int n) { layer.remap_velocity[n].setZero(); });
  constrain(VelocityPhase::kRemap);
}

// Zeroes the control points the step touched, for the next step.
template <int P>
void clear_grid(StepState<P>& st) {
  const PhaseScope timed(st.timer, StepPhase::kClearGrid);
  const int ny = st.grid.ny();
  for (auto& layer : st.layers) {
    const NodeBox& b = layer.active;
#pragma omp parallel for schedule(static) if ((b.i1 - b.i0) * (b.j1 - b.j0) > 4096)
    for (int i = b.i0; i < b.i1; ++i) {
      const int first = i * ny + b.j0, count = b.j1 - b.j0;
      std::fill_n(layer.mass.begin() + first, count, 0.0);
      std::fill_n(layer.momentum.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.force.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.velocity.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.velocity_increment.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.remap_velocity.begin() + first, count, Vec2::Zero());
      if (layer.tracks_mass_gradient) std::fill_n(layer.mass_gradient.begin() + first, count, Vec2::Zero());
      if (layer.tracks_volume) std::fill_n(layer.volume.begin() + first, count, 0.0);
    }
  }
}

}  // namespace bsmpm

// Steps 6 and 7 of docs/method.md §2 in one pass over the particles: the new velocity
// (eq. 11; FLIP blended with PIC, or APIC) and position (eq. 12) from the grid, particle
// shifting (§10), positions a step would carry out of the domain put back inside it, and the
// new momentum scattered back to the grid (eq. 13; update_remap_velocity() divides it by the
// nodal mass).
#pragma once

#include "step/passes/affine_transfer.hpp"
#include "step/passes/grid_to_particle.hpp"
#include "step/passes/particle_shifting.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

// Puts a position that a step carried out of [lo, hi] back on its edge; true if it did.
inline bool keep_inside(Vec2& x, const Vec2& lo, const Vec2& hi) {
  // Component by component: Eigen's == on vectors is an out-of-line call per particle.
  bool moved = false;
  for (int k = 0; k < 2; ++k) {
    const double inside = std::min(std::max(x[k], lo[k]), hi[k]);
    moved = moved || inside != x[k];
    x[k] = inside;
  }
  return moved;
}

// Adds S_Ip q to the particle's control points of `field`.
template <int P>
inline void scatter(const ParticleWeights<P>& w, const Vec2& q, Vec2* field, int ny) {
  for (int a = 0; a <= P; ++a) {
    const int row = (w.i0 + a) * ny + w.j0;
    for (int c = 0; c <= P; ++c) field[row + c] += (w.wx[a] * w.wy[c]) * q;
  }
}

// The pass; returns the number of positions put back inside the domain.
// flip: the FLIP fraction of eq. 11 (1 = the paper); shifting: null when off.
template <int P, bool kAffine>
long move_particles_and_remap_momentum(StepState<P>& st, double dt, double flip,
                                       const ParticleShifting<P>* shifting, const Vec2& floor) {
  const PhaseScope timed(st.timer, StepPhase::kGridToParticle);
  const int ny = st.grid.ny();
  auto& ps = st.particles;
  const double* const gx = st.grid.greville_x();
  const double* const gy = st.grid.greville_y();
  const Vec2 margin = 1e-9 * st.grid.cell_size();
  const Vec2 lo = st.grid.origin() + margin, hi = st.grid.extent_max() - margin;
  long clamped = 0;
  for (std::size_t b = 0; b < st.bodies.size(); ++b) {
    const Body& body = st.bodies[b];
    GridLayer& layer = st.layers[body.layer];
    const RigidBody* rigid = std::get_if<RigidBody>(&body.material);
    const bool shift = shifting && layer.tracks_volume && is_fluid(body.material);
    Vec2* const remap = layer.remap_velocity.data();  // read once (see particle_to_grid.hpp)
    long body_clamped = 0;
    st.schedules[b].for_each([&, remap, gx, gy, ny, dt, flip](std::uint32_t p) {
      // What the scatter reads, as locals: a store to the particle or to the grid may alias
      // the closure, which would reload it (particle_to_grid.hpp).
      const ParticleWeights<P>& w = st.weights[p];
      Vec2* const remap_at = remap;
      const double* const gx_at = gx;
      const double* const gy_at = gy;
      const int ny_at = ny;
      const double dt_at = dt, flip_at = flip;
      GridVelocityAt grid;
      Mat2 C = Mat2::Zero();
      if (kAffine && !rigid) C = gather_velocity_and_affine<P>(w, layer, ny_at, ps.x[p], gx_at, gy_at, floor, grid);
      else grid = gather_velocity<P>(w, layer, ny_at);
      Vec2 v, v_new = grid.velocity;
      if (rigid) {
        v = rigid->velocity;
        v_new = v;
      } else {
        v = flip_at * (ps.v[p] + grid.increment) + (1.0 - flip_at) * v_new;  // eq. 11 (flip = 1: paper)
      }
      const Vec2 x_old = ps.x[p];
      Vec2 x = ps.x[p] + dt_at * v_new;  // eq. 12 with v_I^{k+1}
      if (shift) {
        Vec2 dx = shifting->shift(w, layer.volume, ny_at, x_old, body.layer);
        // A shift never carries a particle out of the domain: that part of it is dropped.
        for (int k = 0; k < 2; ++k)
          if (x[k] + dx[k] < lo[k] || x[k] + dx[k] > hi[k]) dx[k] = 0.0;
        x += dx;
        if constexpr (kAffine)  // else the particle keeps its momentum (method.md §10)
          if (shifting->follows_affine()) v += C * dx;
      }
      ps.v[p] = v;
      if (keep_inside(x, lo, hi)) {
#pragma omp atomic
        ++body_clamped;
      }
      ps.x[p] = x;
      if constexpr (kAffine) {
        ps.C[p] = C;
        scatter_affine<P>(w, ps.mass[p] * v, ps.mass[p] * C, x_old, gx_at, gy_at, remap_at, ny_at);  // eq. 13, affine
      } else {
        scatter<P>(w, ps.mass[p] * v, remap_at, ny_at);  // eq. 13
      }
    });
    clamped += body_clamped;
  }
  return clamped;
}

}  // namespace bsmpm

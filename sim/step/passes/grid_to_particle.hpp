// Grid to particle (docs/method.md §2, steps 6 and 8): what a particle reads from a grid
// field through its weights. The step uses these functions, and the transfer tests call
// them on prescribed nodal fields.
#pragma once

#include <vector>

#include "grid/grid.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

// The grid velocity v_I^{k+1} and its increment v_I^{k+1} - v_I^k at a particle (eqs. 11-12).
struct GridVelocityAt {
  Vec2 velocity = Vec2::Zero();
  Vec2 increment = Vec2::Zero();
};

template <int P>
inline GridVelocityAt gather_velocity(const ParticleWeights<P>& w, const GridLayer& layer, int ny) {
  GridVelocityAt g;
  for (int a = 0; a <= P; ++a) {
    const int row = (w.i0 + a) * ny + w.j0;
    for (int c = 0; c <= P; ++c) {
      const double s = w.wx[a] * w.wy[c];
      g.velocity += s * layer.velocity[row + c];
      g.increment += s * layer.velocity_increment[row + c];
    }
  }
  return g;
}

// Velocity gradient L_p = sum_I v_I (x) grad S_I(x_p^k), L(a, b) = d v_a / d x_b, from the
// remapped velocities; its symmetric part times dt is the strain increment of eq. 14.
// grad S_Ip = (N_a' N_c, N_a N_c'): per column a the sums over c, then the column's factor.
template <int P>
inline Mat2 velocity_gradient(const ParticleWeights<P>& w, const std::vector<Vec2>& v, int ny) {
  Vec2 dx = Vec2::Zero(), dy = Vec2::Zero();  // the columns of L: dv/dx, dv/dy
  for (int a = 0; a <= P; ++a) {
    const Vec2* const vi = v.data() + (w.i0 + a) * ny + w.j0;
    Vec2 along = Vec2::Zero(), across = Vec2::Zero();  // sum_c N_c v, sum_c N_c' v
    for (int c = 0; c <= P; ++c) {
      along += w.wy[c] * vi[c];
      across += w.gy[c] * vi[c];
    }
    dx += w.gx[a] * along;
    dy += w.wx[a] * across;
  }
  Mat2 L;
  L << dx, dy;
  return L;
}

}  // namespace bsmpm

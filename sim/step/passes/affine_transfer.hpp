// The affine particle-in-cell transfer (APIC; Jiang et al. 2015, J. Comput. Phys. 299:1),
// docs/method.md §10: each particle carries an affine velocity C_p besides v_p. The scatter of
// P2G lives in particle_to_grid.hpp; here are the gather of G2P and the remap's scatter.
#pragma once

#include <algorithm>
#include <array>

#include "step/passes/grid_to_particle.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

// Half the interior D_p of APIC (h^2/4 for quadratic, h^2/3 for cubic B-splines): the floor
// of D_p's diagonal next to a clamped wall [m2].
template <int P>
Vec2 affine_floor(const Grid<P>& grid) {
  const double interior = P == 2 ? 0.25 : 1.0 / 3.0;
  return 0.5 * interior * grid.cell_size().cwiseProduct(grid.cell_size());
}

// Adds S_Ip (m v_p + m C_p (xi_I - x_p)) to the particle's control points of `field`.
template <int P>
inline void scatter_affine(const ParticleWeights<P>& w, const Vec2& mv, const Mat2& mC, const Vec2& x,
                           const double* gx, const double* gy, Vec2* field, int ny) {
  for (int a = 0; a <= P; ++a) {
    const int row = (w.i0 + a) * ny + w.j0;
    const Vec2 at_column = mv + (gx[w.i0 + a] - x.x()) * mC.col(0);
    for (int c = 0; c <= P; ++c)
      field[row + c] += (w.wx[a] * w.wy[c]) * (at_column + (gy[w.j0 + c] - x.y()) * mC.col(1));
  }
}

// The grid velocity v_I^{k+1} and its increment at the particle (as gather_velocity()) and
// the APIC affine velocity C_p, in one walk over the particle's control points.
// C_p = B_p D_p^-1 (Jiang et al. 2015, eq. 10) about the control
// points' Greville abscissae, B_p = sum S_Ip v_I (xi_I - x_p)^T, D_p = sum S_Ip (xi_I - x_p)(xi_I - x_p)^T.
// B-splines reproduce linear functions with the Greville points (sum S_Ip xi_I = x_p), which
// is what makes the transfer exact for affine velocity fields and conserve momentum. Next
// to a wall the clamped basis makes D_p vanish like the distance to it; its diagonal is
// floored at half its interior value, so that a lone particle's own pressure cannot drive
// C_p faster than the time step resolves (a particle within ~h/8 of a wall loses part of
// its normal gradient). Linear splines have D_p = 0 at the nodes: there C_p is the gradient
// of the interpolated velocity, sum v_I grad S_Ip^T.
// With tensor-product weights S_Ip = N_a(x) N_c(y), sum_c N_c = 1 and linear reproduction,
// D_p is diagonal, D_xx = sum_a N_a (xi_a - x)^2 and D_yy = sum_c N_c (eta_c - y)^2: it is
// evaluated per axis, and B_p through the row sums of the velocities.
template <int P>
inline Mat2 gather_velocity_and_affine(const ParticleWeights<P>& w, const GridLayer& layer, int ny, const Vec2& x,
                                       const double* gx, const double* gy, const Vec2& floor, GridVelocityAt& g) {
  if constexpr (P == 1) {
    g = gather_velocity<P>(w, layer, ny);
    Mat2 B = Mat2::Zero();
    for (int a = 0; a <= P; ++a) {
      const int row = (w.i0 + a) * ny + w.j0;
      for (int c = 0; c <= P; ++c)
        B += layer.velocity[row + c] * Vec2(w.gx[a] * w.wy[c], w.wx[a] * w.gy[c]).transpose();
    }
    return B;
  } else {
    // Per column a, the sums over c, then over a: S_Ip = N_a N_c factors every sum.
    std::array<double, P + 1> wdy;
    double Dyy = 0.0, Dxx = 0.0;
    for (int c = 0; c <= P; ++c) {
      const double dy = gy[w.j0 + c] - x.y();
      wdy[c] = w.wy[c] * dy;
      Dyy += wdy[c] * dy;
    }
    Vec2 velocity = Vec2::Zero(), increment = Vec2::Zero(), col0 = Vec2::Zero(), col1 = Vec2::Zero();
    const Vec2* const v = layer.velocity.data();
    const Vec2* const dv = layer.velocity_increment.data();
    for (int a = 0; a <= P; ++a) {
      const int row = (w.i0 + a) * ny + w.j0;
      const double dx = gx[w.i0 + a] - x.x();
      Dxx += w.wx[a] * dx * dx;
      // sum_c N_c v, sum_c N_c dv, sum_c N_c dy v
      Vec2 along = Vec2::Zero(), along_increment = Vec2::Zero(), across = Vec2::Zero();
      for (int c = 0; c <= P; ++c) {
        along += w.wy[c] * v[row + c];
        along_increment += w.wy[c] * dv[row + c];
        across += wdy[c] * v[row + c];
      }
      velocity += w.wx[a] * along;
      increment += w.wx[a] * along_increment;
      col0 += (w.wx[a] * dx) * along;
      col1 += w.wx[a] * across;
    }
    g.velocity = velocity;
    g.increment = increment;
    Mat2 B;
    B.col(0) = col0 / std::max(Dxx, floor.x());
    B.col(1) = col1 / std::max(Dyy, floor.y());
    return B;
  }
}

}  // namespace bsmpm

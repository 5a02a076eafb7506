// Step 2 of docs/method.md §2 (P2G): nodal mass (eq. 5), momentum (eq. 6) and internal
// force (eq. 7) of every grid field, in each body's strip order (same bits for any thread
// count; strip_schedule.hpp). With APIC the momentum is the affine field's at the control
// points (docs/method.md §10); contact adds the mass gradients, particle shifting the volumes.
#pragma once

#include <array>

#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class ParticleToGrid {
 public:
  // Scatters every body to its grid field.
  static void scatter(StepState<P>& st, bool affine) {
    const PhaseScope timed(st.timer, StepPhase::kParticleToGrid);
    for (std::size_t b = 0; b < st.bodies.size(); ++b) {
      // Mass gradients only for fields that take part in contact (their normals).
      const GridLayer& layer = st.layers[st.bodies[b].layer];
      const bool gradient = layer.tracks_mass_gradient, volume = layer.tracks_volume;
      if (volume) {
        if (affine) gradient ? body<true, true, true>(st, b) : body<false, true, true>(st, b);
        else gradient ? body<true, false, true>(st, b) : body<false, false, true>(st, b);
      } else {
        if (affine) gradient ? body<true, true, false>(st, b) : body<false, true, false>(st, b);
        else gradient ? body<true, false, false>(st, b) : body<false, false, false>(st, b);
      }
    }
  }

 private:
  template <bool kMassGradient, bool kAffine, bool kVolume>
  static void body(StepState<P>& st, std::size_t b) {
    const int ny = st.grid.ny();
    const Particles& ps = st.particles;
    GridLayer& layer = st.layers[st.bodies[b].layer];
    // Raw pointers, read once: Eigen's vector stores may alias anything, so through the
    // std::vectors every store would reload every array's address.
    double* const mass = layer.mass.data();
    Vec2* const momentum = layer.momentum.data();
    Vec2* const force = layer.force.data();
    Vec2* const mass_gradient = layer.mass_gradient.data();
    double* const volume = layer.volume.data();
    const double* const gx = st.grid.greville_x();
    const double* const gy = st.grid.greville_y();
    const ParticleWeights<P>* const weights = st.weights.data();
    st.schedules[b].for_each([&, mass, momentum, force, mass_gradient, volume, gx, gy, weights](std::uint32_t p) {
      // The fields' addresses as locals: a store to a field may alias the closure, which would
      // reload them at every control point. (A copy of the weights too saves instructions but
      // doubled the pass's time on the elastic gate: the copy's stores stall the loads.)
      const ParticleWeights<P>& w = weights[p];
      double* const mass_at = mass;
      Vec2* const momentum_at = momentum;
      Vec2* const force_at = force;
      Vec2* const mass_gradient_at = mass_gradient;
      double* const volume_at = volume;
      const double m = ps.mass[p];
      const Vec2 mv = m * ps.v[p];
      const double Vp = ps.volume(p);
      const Mat2 Vsigma = Vp * ps.stress[p];
      const Mat2 mC = m * ps.C[p];
      const Vec2 xp = ps.x[p];
      // S_Ip = N_a N_c and grad S_Ip = (N_a' N_c, N_a N_c'): the column's factors first.
      std::array<double, P + 1> dy;
      if constexpr (kAffine)
        for (int c = 0; c <= P; ++c) dy[c] = gy[w.j0 + c] - xp.y();
      for (int a = 0; a <= P; ++a) {
        const int row = (w.i0 + a) * ny + w.j0;
        const double wx = w.wx[a], mx = m * wx;
        // Vsigma grad S_Ip = N_c force_x + N_c' force_y
        const Vec2 force_x = w.gx[a] * Vsigma.col(0), force_y = wx * Vsigma.col(1);
        Vec2 at_column = mv;  // APIC: m (v_p + C_p (xi_I - x_p)) = at_column + dy mC.col(1)
        if constexpr (kAffine) at_column += (gx[w.i0 + a] - xp.x()) * mC.col(0);
        for (int c = 0; c <= P; ++c) {
          const double s = wx * w.wy[c];
          mass_at[row + c] += mx * w.wy[c];  // eq. 5
          if constexpr (kAffine) {
            momentum_at[row + c] += s * (at_column + dy[c] * mC.col(1));
          } else {
            momentum_at[row + c] += s * mv;  // eq. 6 (numerator)
          }
          force_at[row + c] -= w.wy[c] * force_x + w.gy[c] * force_y;  // eq. 7
          if constexpr (kMassGradient)  // contact normals
            mass_gradient_at[row + c] += m * Vec2(w.gx[a] * w.wy[c], wx * w.gy[c]);
          if constexpr (kVolume) volume_at[row + c] += s * Vp;
        }
      }
    });
  }
};

}  // namespace bsmpm

// Particle shifting (docs/method.md §10; after Lind et al. 2012, J. Comput. Phys. 231:1499,
// carried to the grid): phi_I = sum_p S_Ip V_p / integral(N_I) is the volume fraction at the
// control point (1 where particles fill the support evenly); a fluid particle inside the
// water (phi >= 0.95 at it) drifts by -D h^2 grad phi, towards where particles are too sparse.
// Near a free surface or a solid phi drops below the threshold and nothing moves, so the
// surface is not smeared out. Optionally a second drift down the volume fraction at the
// particles' own scale (subcell_volume.hpp) evens the columns the grid's splines cannot see.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "step/passes/subcell_volume.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class ParticleShifting {
 public:
  ParticleShifting() = default;
  // The volume fraction an even lattice of particles (the seeding's, `spacing`) gives at each
  // control point is 1 inside but not next to a wall, where the clamped functions are
  // lopsided: phi is measured against it, so that the seeded state does not drift.
  // subcell_coefficient D_s > 0 adds the sub-cell drift on the grid fields `subcell_layers`.
  // follows_affine: an APIC particle's velocity moves along its affine field (v_p += C_p dx)
  // instead of staying (see follows_affine()).
  ParticleShifting(const Grid<P>& grid, const Vec2& spacing, double coefficient, double subcell_coefficient = 0.0,
                   const std::vector<int>& subcell_layers = {}, bool follows_affine = false)
      : inverse_integral_x_(lattice_fraction_inverse(grid.bx, spacing.x())),
        inverse_integral_y_(lattice_fraction_inverse(grid.by, spacing.y())),
        scale_(coefficient * grid.cell_size().minCoeff() * grid.cell_size().minCoeff()),
        follows_affine_(follows_affine) {
    if (subcell_coefficient <= 0.0) return;
    for (int layer : subcell_layers) {
      if (layer >= static_cast<int>(subcell_.size())) subcell_.resize(layer + 1);
      subcell_[layer].emplace(grid, spacing);
      subcell_scale_ = subcell_coefficient * subcell_[layer]->spacing() * subcell_[layer]->spacing();
    }
    written_.resize(subcell_.size());
  }

  // The sub-cell volumes of every fluid body with the sub-cell drift, scattered from x_p^k in
  // the strips' order (same bits for any thread count); what the last step wrote is zeroed first.
  void scatter_subcell(StepState<P>& st) {
    if (subcell_.empty()) return;
    const PhaseScope timed(st.timer, StepPhase::kParticleToGrid);
    for (std::size_t l = 0; l < subcell_.size(); ++l)
      if (subcell_[l]) {
        subcell_[l]->clear(written_[l]);
        written_[l] = st.layers[l].active;
      }
    const Particles& ps = st.particles;
    for (std::size_t b = 0; b < st.bodies.size(); ++b) {
      const int l = st.bodies[b].layer;
      if (l >= static_cast<int>(subcell_.size()) || !subcell_[l] || !is_fluid(st.bodies[b].material)) continue;
      SubcellVolume<P>& field = *subcell_[l];
      st.schedules[b].for_each([&](std::uint32_t p) { field.add(ps.x[p], ps.volume(p)); });
    }
  }

  // The shift -D h^2 grad phi at the particle, from the volumes of its grid field, plus
  // -D_s s^2 grad phi_s from the sub-cell volumes at x (the particle's x_p^k) when on; zero
  // where phi < 0.95 (near a free surface or a solid).
  Vec2 shift(const ParticleWeights<P>& w, const std::vector<double>& volume, int ny, const Vec2& x,
             int layer) const {
    // phi_I = V_I / (int N_i int N_j) factors per axis: the sums over c first, then over a.
    const std::vector<double>& inv_iy = inverse_integral_y_;
    std::array<double, P + 1> wy, gy;
    for (int c = 0; c <= P; ++c) {
      wy[c] = w.wy[c] * inv_iy[w.j0 + c];
      gy[c] = w.gy[c] * inv_iy[w.j0 + c];
    }
    double phi = 0.0;
    Vec2 grad = Vec2::Zero();
    for (int a = 0; a <= P; ++a) {
      const double* const V = volume.data() + (w.i0 + a) * ny + w.j0;
      double along = 0.0, across = 0.0;  // sum_c N_c V / int N_j, sum_c N_c' V / int N_j
      for (int c = 0; c <= P; ++c) {
        along += wy[c] * V[c];
        across += gy[c] * V[c];
      }
      const double ix = inverse_integral_x_[w.i0 + a];
      phi += w.wx[a] * ix * along;
      grad += ix * Vec2(w.gx[a] * along, w.wx[a] * across);
    }
    if (phi < 0.95) return Vec2::Zero();
    Vec2 dx = -scale_ * grad;
    if (layer < static_cast<int>(subcell_.size()) && subcell_[layer])
      dx -= subcell_scale_ * subcell_[layer]->gradient(x);
    return dx;
  }

  // Whether a shifted APIC particle takes its affine field's velocity at the new position,
  // v_p += C_p dx (method.md §10, solver.shifting_velocity = "affine"); otherwise it keeps v_p,
  // and the shift carries the particle's mass with its momentum: sum m_p v_p is unchanged,
  // where the affine field's velocity changes it by sum m_p C_p dx_p.
  bool follows_affine() const { return follows_affine_; }

  std::size_t bytes() const {
    std::size_t n = heap_bytes(inverse_integral_x_) + heap_bytes(inverse_integral_y_);
    for (const auto& s : subcell_)
      if (s) n += s->bytes();
    return n;
  }

 private:
  // 1 / (sum_k N_i(x_k) dx), over an even lattice x_k = origin + (k + 1/2) dx covering the axis.
  static std::vector<double> lattice_fraction_inverse(const ClampedBSpline<P>& basis, double dx) {
    std::vector<double> sum(basis.basis_count(), 0.0);
    const int count = static_cast<int>(std::lround((basis.end() - basis.origin()) / dx));
    for (int k = 0; k < count; ++k) {
      typename ClampedBSpline<P>::Weights w, dw;
      const int first = basis.evaluate(basis.origin() + (k + 0.5) * dx, w, dw);
      for (int a = 0; a <= P; ++a) sum[first + a] += w[a] * dx;
    }
    for (double& v : sum) v = v > 0.0 ? 1.0 / v : 0.0;
    return sum;
  }

  std::vector<double> inverse_integral_x_, inverse_integral_y_;  // 1 / integral of N_i
  double scale_ = 0.0;                                           // D h_min^2
  std::vector<std::optional<SubcellVolume<P>>> subcell_;         // per grid field; empty when off
  std::vector<NodeBox> written_;                                 // the cells each field's last scatter touched
  double subcell_scale_ = 0.0;                                   // D_s s^2
  bool follows_affine_ = false;                                  // v_p += C_p dx on a shift
};

}  // namespace bsmpm

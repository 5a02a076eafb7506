// Steps 8 and 9 of docs/method.md §2: per body, visiting its material once, the deformation
// from the remapped velocities (eq. 14), then the stress of the material. The fastest signal
// bounds the next time step; a particle whose state turned non-finite or left the density
// range makes the step invalid, and throw_instability() says which and why.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/error.hpp"
#include "core/format.hpp"
#include "step/passes/dilatation_projection.hpp"
#include "step/passes/grid_to_particle.hpp"
#include "step/passes/linear_volume_smoothing.hpp"
#include "step/passes/volume_smoothing.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class StressUpdate {
 public:
  struct Result {
    double max_signal_speed = 0.0;  // largest c + |v|: bounds the next time step
    bool invalid = false;           // some particle's state is non-finite or its density out of range
  };

  StressUpdate() = default;
  StressUpdate(const StepState<P>& st, const SolverSettings& settings)
      : fluid_volume_(settings.fluid_volume),
        j_min_(1.0 / settings.max_density_ratio), j_max_(1.0 / settings.min_density_ratio),
        min_density_ratio_(settings.min_density_ratio), max_density_ratio_(settings.max_density_ratio) {
    const bool incompressible = std::any_of(st.bodies.begin(), st.bodies.end(),
                                            [](const Body& b) { return is_incompressible(b.material); });
    if (fluid_volume_ == SolverSettings::FluidVolume::kProjected || incompressible) {
      projection_ = DilatationProjection<P>(st.grid);
      increment_.resize(st.particles.size());
      gradient_.resize(st.particles.size());
    }
    if (fluid_volume_ == SolverSettings::FluidVolume::kSmoothed) {
      using Basis = SolverSettings::SmoothedVolumeBasis;
      linear_fit_ = settings.smoothed_volume_basis != Basis::kVelocity && P > 1;
      if (linear_fit_)
        linear_smoothing_ = LinearVolumeSmoothing<P>(st.grid, settings.smoothed_values_only,
                                                     settings.smoothed_volume_basis == Basis::kLinearPatches);
      else smoothing_ = VolumeSmoothing<P>(st.grid, settings.smoothed_values_only);
      gradient_.resize(st.particles.size());
    }
  }

  Result update(StepState<P>& st, double dt) {
    const PhaseScope timed(st.timer, StepPhase::kStress);
    Result all;
    for (std::size_t b = 0; b < st.bodies.size(); ++b) {
      const Body& body = st.bodies[b];
      const BodyParticles particles{b, static_cast<long>(body.begin), static_cast<long>(body.end),
                                    st.layers[body.layer].remap_velocity};
      const Result r = std::visit([&](const auto& material) { return update_body(st, particles, material, dt); },
                                  body.material);
      all.max_signal_speed = std::max(all.max_signal_speed, r.max_signal_speed);
      all.invalid = all.invalid || r.invalid;
    }
    return all;
  }

  // Names the first invalid particle and the field that is wrong (a NumericalError the run
  // reports and stops on; the field names are those of io/particle_fields).
  [[noreturn]] void throw_instability(const StepState<P>& st) const {
    const auto& ps = st.particles;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const Body& body = st.bodies[ps.body[p]];
      if (is_rigid(body.material)) continue;
      std::string field;
      if (!ps.x[p].allFinite()) field = "position is not finite";
      else if (!ps.v[p].allFinite()) field = "velocity is not finite";
      else if (!std::isfinite(ps.pressure[p])) field = "pressure is not finite";
      else if (!ps.stress[p].allFinite()) field = "stress_tensor is not finite";
      else if (!std::isfinite(ps.J[p])) field = "volume_ratio is not finite";
      else if (!density_in_range(ps.J[p]))
        field = format("density %.4g rho0 (volume_ratio J = %.4g) is outside the range [%g, %g] rho0 "
                       "(solver.density_range)",
                       1.0 / ps.J[p], ps.J[p], min_density_ratio_, max_density_ratio_);
      else continue;
      throw NumericalError(format(
          "numerical instability at step %ld (t = %.6g s): body '%s', particle %u at (%.4g, %.4g): %s "
          "(|v| = %.3g m/s, p = %.3g Pa); reduce the time step (time.cfl or time.dt)",
          st.step, st.time, body.name.c_str(), ps.id[p], ps.x[p].x(), ps.x[p].y(), field.c_str(), ps.v[p].norm(),
          ps.pressure[p]));
    }
    throw NumericalError(format("numerical instability at step %ld (t = %.6g s): a non-finite state; reduce the "
                                "time step (time.cfl or time.dt)", st.step, st.time));
  }

  std::size_t particle_bytes() const { return heap_bytes(gradient_) + heap_bytes(increment_); }
  std::size_t grid_bytes() const { return smoothing_.bytes() + linear_smoothing_.bytes() + projection_.bytes(); }

 private:
  // One body's particles [begin, end) and the remapped velocities of its grid field.
  struct BodyParticles {
    std::size_t index;
    long begin, end;
    const std::vector<Vec2>& velocity;
  };

  bool density_in_range(double J) const { return J >= j_min_ && J <= j_max_; }
  // Both components finite: Eigen's allFinite() compares x - x with itself, an out-of-line
  // call per particle.
  static bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

  // Fluid: J <- J det(I + dt L), optionally smoothed through the grid, then the pressure of
  // the equation of state and the viscous stress (compiled out when mu = 0).
  Result update_body(StepState<P>& st, const BodyParticles& body, const WeaklyCompressibleFluid& mat, double dt) {
    const int ny = st.grid.ny();
    auto& ps = st.particles;
    double body_speed = 0.0;
    bool body_invalid = false;
    const bool smooth = fluid_volume_ != SolverSettings::FluidVolume::kParticle;
    const bool fitted = fluid_volume_ == SolverSettings::FluidVolume::kSmoothed;
    if (fluid_volume_ == SolverSettings::FluidVolume::kProjected) {
      // The volumetric increment of each particle, projected onto the lower splines (F-bar).
#pragma omp parallel for schedule(static)
      for (long p = body.begin; p < body.end; ++p) {
        const Mat2 L = velocity_gradient<P>(st.weights[p], body.velocity, ny);
        gradient_[p] = L;
        increment_[p] = (Mat2::Identity() + dt * L).determinant() - 1.0;
      }
      {
        const PhaseScope timed(st.timer, StepPhase::kSmoothing);
        projection_.project(st, st.schedules[body.index], body.begin, body.end, increment_);
      }
#pragma omp parallel for schedule(static)
      for (long p = body.begin; p < body.end; ++p) ps.J[p] *= 1.0 + increment_[p];
    } else if (fitted) {
      // One pass in the scatter's order: the velocity gradient, the volume change (eq. 14) and
      // the particle's share of the least-squares moments; then the fit at the control points.
      // The pass below reads the fitted J back before it enters the equation of state.
      const PhaseScope timed(st.timer, StepPhase::kSmoothing);
      auto scatter = [&](auto& smoothing) {
        st.schedules[body.index].for_each([&](std::uint32_t p) {
          const Mat2 L = velocity_gradient<P>(st.weights[p], body.velocity, ny);
          gradient_[p] = L;
          ps.J[p] *= (Mat2::Identity() + dt * L).determinant();
          smoothing.add_moments(st, p);
        });
      };
      if (linear_fit_) {
        linear_smoothing_.begin(st.layers[st.bodies[body.index].layer].active);
        scatter(linear_smoothing_);
        linear_smoothing_.fit();
      } else {
        scatter(smoothing_);
        smoothing_.fit(st.layers[st.bodies[body.index].layer].active, ny);
      }
    }
    // With a tension cut-off, water does not stretch past the J at which it reaches it
    // (method.md §4): a particle there keeps its volume, as water in a thinning sheet does.
    const std::optional<double> j_cut = mat.largest_volume_ratio();
    // J after the step's volume update: read back from the fit, or as updated. One loop per
    // readback, so that each reads its J without a branch per particle.
    auto run = [&](auto viscous, auto&& updated_volume_ratio) {
#pragma omp parallel for schedule(static) reduction(max : body_speed) reduction(|| : body_invalid)
      for (long p = body.begin; p < body.end; ++p) {
        Mat2 L;
        double J;
        if (smooth) {
          L = gradient_[p];
          J = updated_volume_ratio(p);
          ps.J[p] = J;
        } else {
          L = velocity_gradient<P>(st.weights[p], body.velocity, ny);
          J = ps.J[p] * (Mat2::Identity() + dt * L).determinant();
          ps.J[p] = J;
        }
        if (j_cut && J > *j_cut) ps.J[p] = J = *j_cut;
        const double pressure = mat.pressure(J);
        ps.pressure[p] = pressure;
        ps.stress[p] = mat.template stress<decltype(viscous)::value>(pressure, L);
        body_speed = std::max(body_speed, mat.signal_speed(J, ps.v[p].norm()));
        body_invalid = body_invalid || !density_in_range(J) || !std::isfinite(pressure) || !finite(ps.v[p]) ||
                       !finite(ps.x[p]);
      }
    };
    // Viscosity only when mu > 0: the inviscid loop has no deviatoric term at all.
    auto with_readback = [&](auto viscous) {
      if (fitted && linear_fit_) run(viscous, [&](long p) { return linear_smoothing_.fitted_volume_ratio(st, p); });
      else if (fitted) run(viscous, [&](long p) { return smoothing_.fitted_volume_ratio(st, p); });
      else run(viscous, [&](long p) { return ps.J[p]; });
    };
    if (mat.viscosity > 0.0) with_readback(std::true_type{});
    else with_readback(std::false_type{});
    if (fitted && linear_fit_) linear_smoothing_.clear();
    else if (fitted) smoothing_.clear(st.layers[st.bodies[body.index].layer].active, ny);
    return {body_speed, body_invalid};
  }

  // Elastic solid: F <- (I + dt L) F, J = det F, then the hyperelastic Cauchy stress.
  Result update_body(StepState<P>& st, const BodyParticles& body, const ElasticSolid& mat, double dt) {
    const int ny = st.grid.ny();
    auto& ps = st.particles;
    double body_speed = 0.0;
    bool body_invalid = false;
#pragma omp parallel for schedule(static) reduction(max : body_speed) reduction(|| : body_invalid)
    for (long p = body.begin; p < body.end; ++p) {
      const Mat2 L = velocity_gradient<P>(st.weights[p], body.velocity, ny);
      const Mat2 F = (Mat2::Identity() + dt * L) * ps.F[p];
      const double J = F.determinant();
      ps.F[p] = F;
      ps.J[p] = J;
      const Mat2 sigma = mat.stress(F);
      ps.stress[p] = sigma;
      ps.pressure[p] = -0.5 * sigma.trace();
      body_speed = std::max(body_speed, mat.signal_speed(J, ps.v[p].norm()));
      body_invalid = body_invalid || !density_in_range(J) || !sigma.allFinite() || !finite(ps.v[p]) ||
                     !finite(ps.x[p]);
    }
    return {body_speed, body_invalid};
  }

  // Incompressible fluid (method.md §12): the pressure is the projection's (already on the
  // particles); here J and the viscous stress follow the projected velocity v^{k+1} at x^k,
  // the velocity that moved the particles, so that J measures the volume they span. The
  // volume increment is the pressure space's (projected onto the hats, as fluid_volume =
  // "projected" does, method.md §10): the constraint holds the water's volume per hat, not
  // per particle, and a particle's own increment drifts where the spline velocity's
  // divergence does not vanish point by point (at a stagnation point on a wall).
  Result update_body(StepState<P>& st, const BodyParticles& body, const IncompressibleFluid& mat, double dt) {
    const int ny = st.grid.ny();
    auto& ps = st.particles;
    const std::vector<Vec2>& v = st.layers[st.bodies[body.index].layer].velocity;
    const double viscous_speed = mat.viscous_speed(st.grid.cell_size().minCoeff());
    const bool viscous = mat.viscosity > 0.0;
#pragma omp parallel for schedule(static)
    for (long p = body.begin; p < body.end; ++p) {
      const Mat2 L = velocity_gradient<P>(st.weights[p], v, ny);
      increment_[p] = (Mat2::Identity() + dt * L).determinant() - 1.0;
      ps.stress[p] = viscous ? mat.viscous_stress(L) : Mat2::Zero();
    }
    {
      const PhaseScope timed(st.timer, StepPhase::kSmoothing);
      projection_.project(st, st.schedules[body.index], body.begin, body.end, increment_);
    }
    double body_speed = 0.0;
    bool body_invalid = false;
#pragma omp parallel for schedule(static) reduction(max : body_speed) reduction(|| : body_invalid)
    for (long p = body.begin; p < body.end; ++p) {
      const double J = ps.J[p] * (1.0 + increment_[p]);
      ps.J[p] = J;
      body_speed = std::max(body_speed, std::max(mat.signal_speed(J, ps.v[p].norm()), viscous_speed));
      body_invalid = body_invalid || !density_in_range(J) || !std::isfinite(ps.pressure[p]) || !finite(ps.v[p]) ||
                     !finite(ps.x[p]);
    }
    return {body_speed, body_invalid};
  }

  // Rigid body: no deformation, no stress; its prescribed speed still bounds the time step.
  Result update_body(StepState<P>&, const BodyParticles&, const RigidBody& mat, double) {
    return {mat.signal_speed(1.0, 0.0), false};
  }

  SolverSettings::FluidVolume fluid_volume_ = SolverSettings::FluidVolume::kParticle;
  double j_min_ = 0.0, j_max_ = 0.0;  // the density range as volume ratios J = rho0 / rho
  double min_density_ratio_ = 0.0, max_density_ratio_ = 0.0;
  VolumeSmoothing<P> smoothing_;          // only with FluidVolume::kSmoothed on the velocity's splines
  LinearVolumeSmoothing<P> linear_smoothing_;  // only with FluidVolume::kSmoothed on the hats
  bool linear_fit_ = false;
  DilatationProjection<P> projection_;    // only with FluidVolume::kProjected
  std::vector<Mat2> gradient_;            // L_p, kept from the smoothing's pass for the stress pass
  std::vector<double> increment_;         // the projected volumetric increments
};

}  // namespace bsmpm

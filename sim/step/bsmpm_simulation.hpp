// One explicit BSMPM step, MUSL variant (docs/method.md §2; paper eqs. 5-14), for spline order P.
// The step reads as its phases; effects (gravity, walls, contact, ...) plug into the hooks
// declared in effect.hpp and are absent when the scene does not ask for them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "step/dilatation_projection.hpp"
#include "step/effect.hpp"
#include "step/simulation.hpp"
#include "step/step_state.hpp"

namespace bsmpm {

template <int P>
class BsmpmSimulation final : public Simulation {
 public:
  BsmpmSimulation(StepState<P> state, SolverSettings settings,
                  std::vector<std::unique_ptr<Effect<P>>> effects,
                  std::vector<std::unique_ptr<Probe>> probes);

  void advance(double dt) override;
  double max_signal_speed() const override { return max_signal_speed_; }
  double time() const override { return st_.time; }
  long step_count() const override { return st_.step; }
  const Particles& particles() const override { return st_.particles; }
  const std::vector<Body>& bodies() const override { return st_.bodies; }
  const std::vector<std::uint32_t>& index_of_id() const override { return st_.index_of_id; }
  GridInfo grid_info() const override;
  int layer_count() const override { return static_cast<int>(st_.layers.size()); }
  const SimulationStats& stats() const override { return stats_; }
  const StepDiagnostics& last_step() const override { return st_.diagnostics; }
  std::vector<std::string> describe_effects() const override;
  const std::vector<std::unique_ptr<Probe>>& probes() const override { return probes_; }
  void sample_probes() override;
  void restore(Particles particles, const StepCounters& counters, const std::vector<ProbeState>& probes) override;
  void set_phase_timer(PhaseTimer* timer) override { st_.timer = timer; }
  MemoryUse memory_use() const override;

  // Exposed for the unit tests of the transfers.
  StepState<P>& state() { return st_; }
  void compute_weights();
  void particle_to_grid();

 private:
  template <bool kMassGradient, bool kAffine, bool kVolume>
  void scatter_body(std::size_t b);
  void sort_particles_by_cell();
  void update_grid_velocity(double dt);
  template <bool kAffine>
  void move_particles_and_remap_momentum(double dt);
  void update_remap_velocity();
  struct DeformationUpdate {
    double max_signal_speed = 0.0;  // largest c + |v|: bounds the next time step
    bool invalid = false;           // some particle's state is non-finite or its density out of range
  };
  // One body's particles [begin, end) and the remapped velocities of its grid field.
  struct BodyParticles {
    std::size_t index;
    long begin, end;
    const std::vector<Vec2>& velocity;
  };
  DeformationUpdate update_deformation_and_stress(double dt);
  DeformationUpdate update_body(const BodyParticles& body, const WeaklyCompressibleFluid& fluid, double dt);
  DeformationUpdate update_body(const BodyParticles& body, const ElasticSolid& solid, double dt);
  DeformationUpdate update_body(const BodyParticles& body, const RigidBody& rigid, double dt);
  [[noreturn]] void throw_instability() const;
  bool density_in_range(double J) const { return J >= j_min_ && J <= j_max_; }
  // Least-squares smoothing of the fluid's J through the control points (see the .cpp).
  void add_volume_moments(std::uint32_t p);
  void fit_volume_ratio(std::size_t body_index);
  double fitted_volume_ratio(std::size_t p) const;
  void clear_volume_moments(std::size_t body_index);
  void clear_grid();
  void constrain(VelocityPhase phase);

  StepState<P> st_;
  SolverSettings settings_;
  std::vector<std::unique_ptr<Effect<P>>> effects_;
  std::vector<Effect<P>*> force_hooks_, velocity_hooks_;
  std::vector<std::unique_ptr<Probe>> probes_;
  static constexpr int kMoments = 9;
  std::vector<double> smoothing_moments_;  // per control point, only with FluidVolume::kSmoothed
  std::vector<double> greville_x_, greville_y_;
  Vec2 affine_floor_ = Vec2::Zero();        // APIC: floor of D_p's diagonal [m2]
  Vec2 inverse_cell_ = Vec2::Zero();        // 1 / h per axis
  std::vector<double> inverse_integral_x_, inverse_integral_y_;  // 1 / integral of N_i (particle shifting)
  std::vector<Mat2> gradient_scratch_;
  std::vector<std::uint32_t> sort_key_, sort_order_, sort_start_;  // sort_particles_by_cell()
  std::vector<int> column_scratch_;  // compute_weights(): each particle's first column
  Particles::PermuteScratch permute_scratch_;
  DilatationProjection<P> projection_;      // only with FluidVolume::kProjected
  std::vector<double> increment_scratch_;
  double max_signal_speed_ = 0.0;
  double j_min_ = 0.0, j_max_ = 0.0;  // the density range as volume ratios J = rho0 / rho
  SimulationStats stats_;
};

extern template class BsmpmSimulation<1>;
extern template class BsmpmSimulation<2>;
extern template class BsmpmSimulation<3>;

}  // namespace bsmpm

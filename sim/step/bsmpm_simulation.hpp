// One explicit BSMPM step, MUSL variant (docs/method.md §2; paper eqs. 5-14), for spline order P.
// The step reads as its passes (step/passes/, one unit each); effects (gravity, walls,
// contact, ...) plug into the hooks declared in effect.hpp and are absent when the scene does
// not ask for them.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "step/effect.hpp"
#include "step/passes/basis_weights.hpp"
#include "step/passes/particle_shifting.hpp"
#include "step/passes/particle_sort.hpp"
#include "step/passes/particle_to_grid.hpp"
#include "step/passes/stress_update.hpp"
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
  std::vector<double> effect_state() const override;
  MemoryUse memory_use() const override;

  // Exposed for the unit tests of the transfers.
  StepState<P>& state() { return st_; }
  void compute_weights() { basis_.compute(st_); }
  void particle_to_grid() { ParticleToGrid<P>::scatter(st_, affine()); }

 private:
  bool affine() const { return settings_.velocity_update == SolverSettings::VelocityUpdate::kApic; }
  void constrain(VelocityPhase phase);

  StepState<P> st_;
  SolverSettings settings_;
  std::vector<std::unique_ptr<Effect<P>>> effects_;
  std::vector<Effect<P>*> force_hooks_, velocity_hooks_, projection_hooks_;
  std::vector<std::unique_ptr<Probe>> probes_;
  // The passes that keep state from one step to the next (scratch arrays, grids of their own).
  ParticleSort sort_;
  BasisWeights<P> basis_;
  std::optional<ParticleShifting<P>> shifting_;  // only with solver.particle_shifting > 0
  StressUpdate<P> stress_;
  Vec2 affine_floor_ = Vec2::Zero();  // APIC: floor of D_p's diagonal [m2]
  double max_signal_speed_ = 0.0;
  SimulationStats stats_;
};

extern template class BsmpmSimulation<1>;
extern template class BsmpmSimulation<2>;
extern template class BsmpmSimulation<3>;

}  // namespace bsmpm

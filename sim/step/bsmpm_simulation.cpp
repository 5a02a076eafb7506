#include "step/bsmpm_simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/error.hpp"
#include "core/format.hpp"
#include "step/passes/grid_velocity.hpp"
#include "step/passes/move_and_remap.hpp"

namespace bsmpm {

namespace {

std::string describe_material(const Body& b) {
  return std::visit([&](const auto& material) { return material.describe(b.name); }, b.material);
}

}  // namespace

template <int P>
BsmpmSimulation<P>::BsmpmSimulation(StepState<P> state, SolverSettings settings,
                                    std::vector<std::unique_ptr<Effect<P>>> effects,
                                    std::vector<std::unique_ptr<Probe>> probes)
    : st_(std::move(state)), settings_(settings), effects_(std::move(effects)), probes_(std::move(probes)),
      stress_(st_, settings_), affine_floor_(affine_floor(st_.grid)) {
  // The order of the effects' phases, not the order they were given in (EffectPhase).
  std::stable_sort(effects_.begin(), effects_.end(),
                   [](const auto& a, const auto& b) { return a->phase() < b->phase(); });
  for (auto& e : effects_) {
    if (e->hooks() & kHookGridForces) force_hooks_.push_back(e.get());
    if (e->hooks() & kHookConstrainVelocity) velocity_hooks_.push_back(e.get());
    if (e->hooks() & kHookProjectVelocity) projection_hooks_.push_back(e.get());
  }
  st_.schedules.resize(st_.bodies.size());
  st_.weights.resize(st_.particles.size());
  if (settings_.shifting > 0.0 || settings_.subcell_shifting > 0.0) {
    std::optional<Vec2> spacing;  // the first fluid's seeding lattice (particle_shifting.hpp)
    std::vector<int> fluid_layers;
    for (const Body& b : st_.bodies)
      if (is_fluid(b.material)) {
        st_.layers[b.layer].tracks_volume = true;
        fluid_layers.push_back(b.layer);
        if (!spacing) spacing = b.spacing;
      }
    shifting_.emplace(st_.grid, spacing.value_or(st_.grid.cell_size() / 2.0), settings_.shifting,
                      settings_.subcell_shifting, fluid_layers, settings_.shift_follows_affine);
  }
  for (auto& layer : st_.layers) layer.resize(st_.grid.node_count());
  st_.index_of_id.resize(st_.particles.size());
  for (std::size_t p = 0; p < st_.particles.size(); ++p) st_.index_of_id[st_.particles.id[p]] = p;
  // The cut-off scales with the lightest deformable particle: a rigid body's density is a
  // free parameter (it is infinitely heavy in the contact) and must not move the cut-off.
  double lightest = std::numeric_limits<double>::infinity(), lightest_rigid = lightest;
  for (const Body& b : st_.bodies) {
    double& bound = is_rigid(b.material) ? lightest_rigid : lightest;
    for (std::size_t p = b.begin; p < b.end; ++p) bound = std::min(bound, st_.particles.mass[p]);
  }
  st_.mass_cutoff = settings_.mass_cutoff_ratio * (std::isfinite(lightest) ? lightest : lightest_rigid);
  for (const Body& b : st_.bodies)
    for (std::size_t p = b.begin; p < b.end; ++p)
      max_signal_speed_ = std::max(
          max_signal_speed_, signal_speed(b.material, st_.particles.J[p], st_.particles.v[p].norm()));
  sort_.sort(st_);
}

template <int P>
GridInfo BsmpmSimulation<P>::grid_info() const {
  return {P, st_.grid.origin(), st_.grid.cell_size(), st_.grid.bx.cells(), st_.grid.by.cells()};
}

template <int P>
MemoryUse BsmpmSimulation<P>::memory_use() const {
  MemoryUse m;
  m.particles = st_.particles.size();
  m.control_points = static_cast<std::size_t>(st_.grid.node_count());
  m.particle_bytes = st_.particles.bytes() + heap_bytes(st_.weights) + heap_bytes(st_.index_of_id) +
                     sort_.particle_bytes() + basis_.bytes() + stress_.particle_bytes();
  for (const StripSchedule& s : st_.schedules) m.particle_bytes += s.bytes();
  m.grid_bytes = stress_.grid_bytes() + sort_.cell_bytes() + (shifting_ ? shifting_->bytes() : 0);
  for (const GridLayer& layer : st_.layers) m.grid_bytes += layer.bytes();
  return m;
}

template <int P>
std::vector<std::string> BsmpmSimulation<P>::describe_effects() const {
  std::vector<std::string> lines;
  for (const Body& b : st_.bodies)
    if (std::string line = describe_material(b); !line.empty()) lines.push_back(line);
  for (const auto& e : effects_) lines.push_back(e->describe());
  for (const auto& p : probes_) lines.push_back("probe " + p->describe());
  return lines;
}

template <int P>
void BsmpmSimulation<P>::sample_probes() {
  if (probes_.empty()) return;
  const PhaseScope timed(st_.timer, StepPhase::kProbes);
  const ProbeContext ctx{st_.particles, st_.bodies, st_.index_of_id, st_.time, &st_.diagnostics.wall_impulse, st_.dt};
  for (auto& probe : probes_) probe->maybe_sample(ctx);
}

template <int P>
void BsmpmSimulation<P>::restore(Particles particles, const StepCounters& counters,
                                 const std::vector<ProbeState>& probes) {
  if (particles.size() != st_.particles.size() || probes.size() != probes_.size())
    throw std::invalid_argument("restore: the state is not of this scene");
  st_.particles = std::move(particles);
  for (std::size_t p = 0; p < st_.particles.size(); ++p) st_.index_of_id[st_.particles.id[p]] = p;
  st_.time = counters.time;
  st_.step = counters.step;
  max_signal_speed_ = counters.max_signal_speed;
  stats_ = counters.stats;
  std::size_t at = 0;
  for (auto& e : effects_) at = e->load_state(counters.effect_state, at);
  if (at != counters.effect_state.size()) throw std::invalid_argument("restore: the effects' state is not of this scene");
  for (std::size_t k = 0; k < probes.size(); ++k) probes_[k]->restore(probes[k]);
}

template <int P>
std::vector<double> BsmpmSimulation<P>::effect_state() const {
  std::vector<double> out;
  for (const auto& e : effects_) e->save_state(out);
  return out;
}

// The step of docs/method.md §2, pass by pass.
template <int P>
void BsmpmSimulation<P>::advance(double dt) {
  const PhaseScope timed(st_.timer, StepPhase::kOther);  // each pass times itself (phase_timer.hpp)
  st_.dt = dt;
  st_.diagnostics.reset();
  if (settings_.sort_interval > 0 && st_.step > 0 && st_.step % settings_.sort_interval == 0) sort_.sort(st_);
  basis_.compute(st_);                                      // step 1
  ParticleToGrid<P>::scatter(st_, affine());                // step 2: eqs. 5-7
  if (shifting_) shifting_->scatter_subcell(st_);           // §10: the sub-cell volumes, when on
  for (auto* e : force_hooks_) {                            // step 3: eq. 8
    const PhaseScope timed(st_.timer, StepPhase::kEffects);
    e->grid_forces(st_);
  }
  const auto constrain = [this](VelocityPhase phase) { this->constrain(phase); };
  update_grid_velocity(st_, dt, constrain);                 // steps 4-5: eqs. 9-10, essential conditions
  stats_.work += st_.diagnostics.work;                      // what the constraints did to the motion
  stats_.pressure.add(st_.diagnostics.pressure);            // an incompressible fluid's solve (method.md §12)
  const ParticleShifting<P>* shifting = shifting_ ? &*shifting_ : nullptr;
  stats_.clamped_positions +=                               // step 6 and the remap's scatter: eqs. 11-13
      affine() ? move_particles_and_remap_momentum<P, true>(st_, dt, settings_.flip_fraction, shifting, affine_floor_)
               : move_particles_and_remap_momentum<P, false>(st_, dt, settings_.flip_fraction, shifting, affine_floor_);
  update_remap_velocity(st_, constrain);                    // step 7: eq. 13, essential conditions
  const auto update = stress_.update(st_, dt);              // steps 8-9: eq. 14, the constitutive update
  max_signal_speed_ = update.max_signal_speed;              // bounds the next time step (CFL)
  clear_grid(st_);
  st_.time += dt;
  ++st_.step;
  // After the counters: the state the error describes (and the run writes out) is this step's.
  if (update.invalid) stress_.throw_instability(st_);
  sample_probes();
}

// The essential conditions; in the update phase then the projection of an incompressible
// fluid's velocity (method.md §12), which sees every constraint and which the FLIP increment
// and the particles see.
template <int P>
void BsmpmSimulation<P>::constrain(VelocityPhase phase) {
  for (auto* e : velocity_hooks_) {
    const PhaseScope timed(st_.timer, st_.timer && e->phase() == EffectPhase::kContact ? StepPhase::kContact
                                                                                         : StepPhase::kEffects);
    e->constrain_velocity(st_, phase);
  }
  if (phase != VelocityPhase::kUpdate) return;
  for (auto* e : projection_hooks_) {
    const PhaseScope timed(st_.timer, StepPhase::kProjection);
    e->project_velocity(st_);
  }
}

template class BsmpmSimulation<1>;
template class BsmpmSimulation<2>;
template class BsmpmSimulation<3>;

}  // namespace bsmpm

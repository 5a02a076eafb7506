// The solver as the command-line program and the tests see it: one interface over the
// three spline orders (the order is a template parameter inside; see bsmpm_simulation.hpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "particles/body.hpp"
#include "particles/particles.hpp"
#include "probes/probe.hpp"

namespace bsmpm {

struct GridInfo {
  int order = 2;
  Vec2 origin = Vec2::Zero();
  Vec2 cell_size = Vec2::Zero();
  int cells_x = 0, cells_y = 0;
  Vec2 extent_max() const { return origin + Vec2(cell_size.x() * cells_x, cell_size.y() * cells_y); }
};

struct SolverSettings {
  // The particle velocity update (docs/method.md §2): FLIP (eq. 11, blended with PIC by
  // flip_fraction) or APIC, an affine particle velocity (Jiang et al. 2015).
  enum class VelocityUpdate { kFlip, kApic };
  VelocityUpdate velocity_update = VelocityUpdate::kFlip;
  double flip_fraction = 1.0;        // 1 = pure FLIP increment (eq. 11); 0 = PIC
  double mass_cutoff_ratio = 1e-6;   // nodal mass cut-off, relative to the lightest particle
  int sort_interval = 50;            // steps between re-sorting particles by cell
  // How a fluid's volume ratio J follows the flow (docs/method.md §4).
  enum class FluidVolume {
    kParticle,   // J <- J det(I + dt L_p) at each particle (the paper)
    kSmoothed,   // the same, then J itself fitted through the control points each step
    kProjected,  // the increment projected onto the splines one degree lower (F-bar)
  };
  FluidVolume fluid_volume = FluidVolume::kParticle;
  // Particle shifting (docs/method.md §4): fluid particles drift down the gradient of the
  // grid's volume fraction, D = shifting h^2 per step; 0 = off (the paper).
  double shifting = 0.0;
};

// What the last step did, for tests and diagnostics.
struct StepDiagnostics {
  int contact_nodes = 0;         // control points where a contact force acted
  double contact_impulse = 0.0;  // sum of |f_contact| dt over them [N s / m]
};

// Heap bytes the solver holds, by what they scale with (bsmpm bench reports them per item).
struct MemoryUse {
  std::size_t particle_bytes = 0;  // per-particle arrays: state, basis weights, schedules, scratch
  std::size_t grid_bytes = 0;      // per-control-point arrays: the grid layers, smoothing moments
  std::size_t particles = 0, control_points = 0;
};

class PhaseTimer;

struct SimulationStats {
  long clamped_positions = 0;  // particle positions pushed back inside the domain
};

class Simulation {
 public:
  virtual ~Simulation() = default;

  // One MUSL step of size dt (docs/method.md §2, eqs. 5-14).
  virtual void advance(double dt) = 0;
  // Largest c + |v| over the particles after the last step (for the CFL time step).
  virtual double max_signal_speed() const = 0;

  virtual double time() const = 0;
  virtual long step_count() const = 0;
  virtual const Particles& particles() const = 0;
  virtual const std::vector<Body>& bodies() const = 0;
  virtual const std::vector<std::uint32_t>& index_of_id() const = 0;
  virtual GridInfo grid_info() const = 0;
  virtual int layer_count() const = 0;
  virtual const SimulationStats& stats() const = 0;
  virtual const StepDiagnostics& last_step() const = 0;
  // The effects this scene composed, one line each, in the order the step runs them.
  virtual std::vector<std::string> describe_effects() const = 0;
  virtual const std::vector<std::unique_ptr<Probe>>& probes() const = 0;
  // Samples every probe at the current state (the step does this after each advance()).
  virtual void sample_probes() = 0;
  // Times each phase of the steps that follow into `timer` (step/phase_timer.hpp); null,
  // the default, times nothing.
  virtual void set_phase_timer(PhaseTimer*) {}
  virtual MemoryUse memory_use() const { return {}; }
};

}  // namespace bsmpm

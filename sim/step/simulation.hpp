// The solver as the command-line program and the tests see it: one interface over the
// three spline orders (the order is a template parameter inside; see bsmpm_simulation.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
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
  // With kSmoothed, what each particle reads back from the control points' fits (method.md
  // §4): their values and gradients, J_I + g_I . (x_p - xi_I) (false), or their values only,
  // J_I (true: particles bunched at the knots no longer pass their J through unsmoothed).
  bool smoothed_values_only = false;
  // With kSmoothed, where the fit is made (method.md §4): at the velocity's control points with
  // their splines as weights, or at the knots (the linear splines' control points) with the
  // hats as weights or with weight 1 over each knot's four cells (kLinearPatches: a particle
  // adds to one cell's moments, carried to the knots on the grid).
  enum class SmoothedVolumeBasis { kVelocity, kLinear, kLinearPatches };
  SmoothedVolumeBasis smoothed_volume_basis = SmoothedVolumeBasis::kVelocity;
  // Particle shifting (docs/method.md §10): fluid particles drift down the gradient of the
  // grid's volume fraction, D = shifting h^2 per step; 0 = off (the paper).
  double shifting = 0.0;
  // Sub-cell shifting (docs/method.md §10): the same drift down the volume fraction at the
  // particles' own spacing s, D_s = subcell_shifting s^2 per step; 0 = off.
  double subcell_shifting = 0.0;
  // What a shifted APIC particle's velocity does (docs/method.md §10): kept (false: the shift
  // moves mass with its momentum, so momentum is conserved exactly) or moved along its affine
  // field, v_p += C_p dx (true: the velocity at the new position; momentum changes by m C dx).
  bool shift_follows_affine = false;
  // rho / rho0 = 1 / J that a deformable particle may reach: beyond it the step stops the
  // run as numerically unstable (solver.density_range; docs/method.md §2).
  double min_density_ratio = 0.5, max_density_ratio = 2.0;
};

// What the essential conditions did to the motion in the update phase of a step
// (docs/method.md §2, step 5) [J/m]. Walls, clamps and contact between deformable bodies are
// at rest relative to what they hold: their mechanical work is zero, and what is recorded is
// the nodal kinetic energy they take, m_I (|v_after|^2 - |v_before|^2) / 2 summed over the
// control points (<= 0: the inelastic loss of an impact). A rigid body moving at v_R pushes
// with the impulse it gives: its work is impulse . v_R, work from outside.
// The remap phase (step 7) is left out: it shapes the strain increment, not the motion.
struct ConstraintWork {
  double walls = 0.0;          // kinetic energy the tank walls take (<= 0)
  double clamps = 0.0;         // kinetic energy the clamps take (<= 0)
  double contact = 0.0;        // kinetic energy contact between deformable bodies takes (<= 0)
  double rigid_contact = 0.0;  // work of the rigid bodies' push on the deformable ones

  ConstraintWork& operator+=(const ConstraintWork& o) {
    walls += o.walls;
    clamps += o.clamps;
    contact += o.contact;
    rigid_contact += o.rigid_contact;
    return *this;
  }
  // The work done from outside the deformable bodies (gravity aside, which their potential
  // energy holds): only moving rigid bodies do any.
  double external() const { return rigid_contact; }
};

// The impulses of one contact pair in the update phase: on body r, at the control points
// where a contact force acted (body s received the opposite, unless rigid) [N s/m].
struct ContactImpulses {
  std::vector<int> nodes;
  std::vector<Vec2> impulse;
};

// The pressure solve of the incompressible fluid in one step (docs/method.md §12).
struct PressureSolve {
  int unknowns = 0;       // vertices whose pressure was solved for (0: no solve this step)
  int iterations = 0;     // conjugate-gradient iterations
  double residual = 0.0;  // |b - A p| / |b| at the end
};

// What the last step did, for tests and diagnostics (and, later, wall-pressure sensors).
struct StepDiagnostics {
  int contact_nodes = 0;         // control points where a contact force acted
  double contact_impulse = 0.0;  // sum of |f_contact| dt over them [N s / m]
  ConstraintWork work;           // this step's work of the constraints
  // Per wall side (WallSide), per control point along it (index j on the left and right
  // walls, i on the bottom and top): the impulse m_I (v_after - v_before) the wall gave the
  // deformable fields [N s/m]; its normal part over dt is the wall's reaction force there.
  std::array<std::vector<Vec2>, 4> wall_impulse;
  std::vector<ContactImpulses> contact;  // per pair of the contact effect
  PressureSolve pressure;                // the incompressible fluid's, if any

  // Zeroes everything for the next step, keeping the arrays' storage.
  void reset() {
    pressure = PressureSolve{};
    contact_nodes = 0;
    contact_impulse = 0.0;
    work = ConstraintWork{};
    for (auto& side : wall_impulse) std::fill(side.begin(), side.end(), Vec2::Zero());
    for (auto& pair : contact) {
      pair.nodes.clear();
      pair.impulse.clear();
    }
  }
};

// Heap bytes the solver holds, by what they scale with (bsmpm bench reports them per item).
struct MemoryUse {
  std::size_t particle_bytes = 0;  // per-particle arrays: state, basis weights, schedules, scratch
  std::size_t grid_bytes = 0;      // per-control-point arrays: the grid layers, smoothing moments
  std::size_t particles = 0, control_points = 0;
};

class PhaseTimer;

// Counters over the whole run (a checkpoint holds them).
// The pressure solves of a run (docs/method.md §12): their count, iterations and residuals.
struct PressureSolveStats {
  long solves = 0;
  long iterations = 0;          // summed over the solves
  int max_iterations = 0;
  double max_residual = 0.0;
  void add(const PressureSolve& s) {
    if (s.unknowns == 0) return;
    ++solves;
    iterations += s.iterations;
    max_iterations = std::max(max_iterations, s.iterations);
    max_residual = std::max(max_residual, s.residual);
  }
};

struct SimulationStats {
  long clamped_positions = 0;  // particle positions pushed back inside the domain
  ConstraintWork work;         // the constraints' work since t = 0 [J/m]
  PressureSolveStats pressure; // the incompressible fluid's solves
};

// The state of a run between two steps beyond its particles, which a checkpoint holds so
// that a resumed run continues bit for bit.
struct StepCounters {
  double time = 0.0;
  long step = 0;
  double max_signal_speed = 0.0;  // bounds the next time step (docs/method.md §7)
  SimulationStats stats;
  std::vector<double> effect_state;  // what the effects carry between steps (Effect::save_state)
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
  StepCounters counters() const { return {time(), step_count(), max_signal_speed(), stats(), effect_state()}; }
  // The effects' state between steps (Effect::save_state), in their order.
  virtual std::vector<double> effect_state() const { return {}; }
  // Replaces the particles (in slot order, as particles() holds them), the counters and the
  // probes' states with a checkpoint's; the next advance() then continues as the run that
  // wrote it would have. The particles must be those this scene seeds (same count and bodies).
  virtual void restore(Particles, const StepCounters&, const std::vector<ProbeState>&) {
    throw std::logic_error("this simulation cannot be restored from a checkpoint");
  }
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

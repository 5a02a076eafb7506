// Wall time per phase of the step, for `bsmpm bench` (docs/validation.md, speed). The step
// holds a PhaseTimer pointer that is null outside a benchmark: each phase boundary then
// costs one pointer test. With a timer, a boundary reads the clock once and charges the time
// since the previous boundary to the phase that was running, so the phases are exclusive
// (contact inside the grid update is not counted twice) and sum to the time measured.
// Boundaries sit only in serial code, between parallel loops.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>

namespace bsmpm {

enum class StepPhase : int {
  kOutside,         // between steps: choosing the time step (the bench loop)
  kOther,           // inside advance() but in no phase below
  kSort,            // particles re-sorted by cell
  kWeights,         // basis values at the particles, scatter schedules, active boxes
  kParticleToGrid,  // mass, momentum, internal force (eqs. 5-7)
  kEffects,         // effects' grid forces (eq. 8) and velocity constraints other than contact
  kContact,         // multi-body contact (EffectPhase::kContact)
  kGridUpdate,      // nodal velocities (eqs. 9-10) and the remapped velocities (eq. 13)
  kProjection,      // the incompressible fluid's pressure: operator, solve, correction (method.md §12)
  kGridToParticle,  // G2P, positions and the momentum remap in one pass (eqs. 11-13)
  kStress,          // velocity gradient, deformation and constitutive update (eq. 14)
  kSmoothing,       // the fluid volume ratio fitted through the grid; for such a fluid, its
                    // pass takes the velocity gradient and J too (one walk over the particles)
  kClearGrid,       // the touched control points zeroed for the next step
  kProbes,          // probe sampling after the step
  kCount
};

inline constexpr std::size_t kStepPhaseCount = static_cast<std::size_t>(StepPhase::kCount);

// Names as they appear in bench's output and JSON record.
inline constexpr std::array<const char*, kStepPhaseCount> kStepPhaseNames = {
    "outside", "other", "sort", "weights", "particle_to_grid", "effects", "contact",
    "grid_update", "projection", "grid_to_particle", "stress", "smoothing", "clear_grid", "probes"};

class PhaseTimer {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts charging time to `phase` from now, with all totals zero.
  void reset(StepPhase phase = StepPhase::kOutside) {
    seconds_.fill(0.0);
    current_ = phase;
    last_ = Clock::now();
  }
  // Charges the time since the last boundary to the running phase; `next` runs from now.
  // Returns the phase that was running.
  StepPhase switch_to(StepPhase next) {
    const Clock::time_point now = Clock::now();
    seconds_[static_cast<std::size_t>(current_)] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
    const StepPhase previous = current_;
    current_ = next;
    return previous;
  }
  double seconds(StepPhase phase) const { return seconds_[static_cast<std::size_t>(phase)]; }
  double seconds(std::size_t phase) const { return seconds_[phase]; }

 private:
  std::array<double, kStepPhaseCount> seconds_{};
  StepPhase current_ = StepPhase::kOutside;
  Clock::time_point last_ = Clock::now();
};

// Runs `phase` for the scope's lifetime, then returns to the phase that was running.
class PhaseScope {
 public:
  PhaseScope(PhaseTimer* timer, StepPhase phase) : timer_(timer) {
    if (timer_) previous_ = timer_->switch_to(phase);
  }
  ~PhaseScope() {
    if (timer_) timer_->switch_to(previous_);
  }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  PhaseTimer* timer_;
  StepPhase previous_ = StepPhase::kOther;
};

}  // namespace bsmpm

// Local non-viscous damping (Cundall 1987, as used for quasi-static initialisation in
// geomechanics MPM codes): each nodal force component is reduced by alpha |f| against the
// direction of motion, f_i -= alpha |f_i| sign(v_i). It removes the acoustic ringing of a
// body released from an unbalanced state and vanishes at equilibrium (f = 0). Off unless a
// scene sets solver.local_damping > 0; it is not part of the paper's method.
#pragma once

#include <cmath>
#include <memory>
#include <optional>

#include "core/format.hpp"
#include "step/effects/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// solver.local_damping = alpha in [0, 1), 0 (off) by default.
struct LocalDampingParameters {
  double alpha = 0.0;

  static std::optional<LocalDampingParameters> read(SceneTables& scene) {
    if (!scene.solver) return std::nullopt;
    const double alpha = scene.solver->number_or("local_damping", 0.0, Range{Bound::inclusive(0.0), Bound::exclusive(1.0)});
    if (!(alpha > 0.0)) return std::nullopt;
    return LocalDampingParameters{alpha};
  }
};

template <int P>
class LocalDamping final : public EffectBase<LocalDamping<P>, P> {
 public:
  using Parameters = LocalDampingParameters;
  // After every force is in: the damping scales the nodal force sum.
  static constexpr EffectPhase kPhase = EffectPhase::kForceDamping;
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>&) {
    return std::make_unique<LocalDamping>(p.alpha);
  }

  explicit LocalDamping(double alpha) : alpha_(alpha) {}

  std::string describe() const override {
    return format("local damping: alpha = %g (Cundall, not in the paper)", alpha_);
  }
  void grid_forces(StepState<P>& st) override {
    const int ny = st.grid.ny();
    for (auto& layer : st.layers)
      for_each_node(layer.active, ny, [&](int n, int, int) {
        Vec2& f = layer.force[n];
        const Vec2& momentum = layer.momentum[n];  // same sign as the velocity
        for (int d = 0; d < 2; ++d)
          if (momentum[d] != 0.0) f[d] -= alpha_ * std::abs(f[d]) * (momentum[d] > 0.0 ? 1.0 : -1.0);
      });
  }

 private:
  double alpha_;
};

}  // namespace bsmpm

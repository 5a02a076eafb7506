// Body force m g on the control points (eq. 8, first term): since sum_p m_p b S_Ip =
// m_I b for a uniform b, gravity costs one pass over the active nodes, not over particles.
// A bed slope theta rotates gravity in the tank frame (paper Fig. 9; the reading in
// docs/method.md §2, step 3).
#pragma once

#include <cmath>
#include <memory>
#include <optional>

#include "core/format.hpp"
#include "step/effects/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// [gravity] g = 9.81 (m/s2; 0 turns gravity off), slope_deg = 0 (in [-60, 60]). Hydrostatic
// seeding and the reference scales use these too.
struct GravityParameters {
  double g = 9.81;
  double slope_deg = 0.0;

  // The gravity vector in the tank frame.
  Vec2 vector() const {
    const double theta = slope_deg * kPi / 180.0;
    return {g * std::sin(theta), -g * std::cos(theta)};
  }

  // Absent when g = 0: the scene then has no gravity at all.
  static std::optional<GravityParameters> read(SceneTables& scene) {
    GravityParameters p;
    if (auto t = scene.root.optional_table("gravity")) {
      p.g = t->number_or("g", p.g, Range::non_negative());
      p.slope_deg = t->number_or("slope_deg", p.slope_deg, Range::closed(-60.0, 60.0));
      t->finish();
    }
    if (!(p.g > 0.0)) return std::nullopt;
    return p;
  }
};

template <int P>
class Gravity final : public EffectBase<Gravity<P>, P> {
 public:
  using Parameters = GravityParameters;
  static constexpr EffectPhase kPhase = EffectPhase::kBodyForce;
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>&) {
    return std::make_unique<Gravity>(p);
  }

  explicit Gravity(const Parameters& p) : p_(p), b_(p.vector()) {}

  std::string describe() const override {
    return format("gravity: g = %g m/s2, bed slope %g deg (g = [%.4g, %.4g])", p_.g, p_.slope_deg, b_.x(), b_.y());
  }
  void grid_forces(StepState<P>& st) override {
    const int ny = st.grid.ny();
    for (auto& layer : st.layers)
      for_each_node_parallel(layer.active, ny, [&](int n, int, int) { layer.force[n] += layer.mass[n] * b_; });
  }

 private:
  Parameters p_;
  Vec2 b_;
};

}  // namespace bsmpm

// The domain's four sides as walls (the tank; docs/method.md §3 and §2, step 5). The
// clamped basis interpolates at the boundary, so only the outermost control points lie on
// a wall, and the velocity there is the velocity of the wall line itself.
//  - slip:     free slip that lets water leave the wall: the normal velocity is removed
//              only when it points into the wall (v.n_out > 0). Whether a control point
//              is held is decided on v_I^{k+1} and the same decision is applied to the
//              remapped velocity, so the strain increment sees the wall the step saw.
//  - symmetry: zero normal velocity both ways, a mirror plane (the paper's "symmetric"
//              boundary); water cannot leave such a wall, so it clings to a tank's lid
//  - no_slip:  zero velocity
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/boundaries.hpp"
#include "parameters/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// [domain.walls] left, right, bottom, top = "slip" (default), "symmetry" or "no_slip".
struct TankWallParameters {
  std::array<WallKind, 4> kinds{WallKind::kSlip, WallKind::kSlip, WallKind::kSlip, WallKind::kSlip};

  // Every scene has the tank's walls.
  static std::optional<TankWallParameters> read(SceneTables& scene) {
    TankWallParameters p;
    if (auto walls = scene.domain.optional_table("walls")) {
      for (int side = 0; side < 4; ++side) {
        const std::string kind = walls->choice_or(wall_side_name(side), "slip", {"slip", "symmetry", "no_slip"});
        p.kinds[side] = kind == "slip" ? WallKind::kSlip : kind == "symmetry" ? WallKind::kSymmetry : WallKind::kNoSlip;
      }
      walls->finish();
    }
    return p;
  }
};

template <int P>
class TankWalls final : public EffectBase<TankWalls<P>, P> {
 public:
  using Parameters = TankWallParameters;
  static constexpr EffectPhase kPhase = EffectPhase::kWalls;
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>& st) {
    std::vector<char> rigid(st.layers.size(), 0);
    for (const Body& b : st.bodies)
      if (is_rigid(b.material)) rigid[b.layer] = 1;
    return std::make_unique<TankWalls>(p.kinds, std::move(rigid));
  }

  TankWalls(std::array<WallKind, 4> kinds, std::vector<char> rigid_layer = {})
      : kinds_(kinds), rigid_layer_(std::move(rigid_layer)) {}

  std::string describe() const override {
    std::string s = "tank walls:";
    for (int side = 0; side < 4; ++side)
      s += std::string(" ") + wall_side_name(side) + " " + wall_kind_name(kinds_[side]);
    return s;
  }

  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override {
    const int nx = st.grid.nx(), ny = st.grid.ny();
    const bool update = phase == VelocityPhase::kUpdate;
    auto& impulse = st.diagnostics.wall_impulse;
    if (update) {
      impulse[kLeft].resize(ny); impulse[kRight].resize(ny); impulse[kBottom].resize(nx); impulse[kTop].resize(nx);
    }
    held_.resize(st.layers.size());
    for (std::size_t l = 0; l < st.layers.size(); ++l) {
      GridLayer& layer = st.layers[l];
      if (layer.active.empty()) continue;
      auto& v = phase_velocity(layer, phase);
      auto& held = held_[l];
      held[kLeft].resize(ny); held[kRight].resize(ny); held[kBottom].resize(nx); held[kTop].resize(nx);
      const NodeBox& b = layer.active;
      // The update phase records what the wall did to a deformable field (StepDiagnostics):
      // the impulse per control point and the work; a rigid body's field is prescribed.
      const bool record = update && !(l < rigid_layer_.size() && rigid_layer_[l]);
      auto hold = [&](int n, int side, int axis, double outward, int k) {
        const Vec2 before = v[n];
        apply(v[n], side, axis, outward, held[side][k], update);
        if (!record || !(layer.mass[n] > st.mass_cutoff)) return;
        const double m = layer.mass[n];
        impulse[side][k] += m * (v[n] - before);
        st.diagnostics.work.walls += 0.5 * m * (v[n].squaredNorm() - before.squaredNorm());
      };
      if (b.i0 == 0) for (int j = b.j0; j < b.j1; ++j) hold(j, kLeft, 0, -1.0, j);
      if (b.i1 == nx) for (int j = b.j0; j < b.j1; ++j) hold((nx - 1) * ny + j, kRight, 0, 1.0, j);
      if (b.j0 == 0) for (int i = b.i0; i < b.i1; ++i) hold(i * ny, kBottom, 1, -1.0, i);
      if (b.j1 == ny) for (int i = b.i0; i < b.i1; ++i) hold(i * ny + ny - 1, kTop, 1, 1.0, i);
    }
  }

 private:
  // `outward` is the sign of the wall's outward normal along `axis`; `held` records the
  // separable-slip decision of the update phase for the remap phase.
  void apply(Vec2& v, int side, int axis, double outward, char& held, bool update) const {
    switch (kinds_[side]) {
      case WallKind::kSlip:
        if (update) held = v[axis] * outward > 0.0;
        if (held) v[axis] = 0.0;
        break;
      case WallKind::kSymmetry: v[axis] = 0.0; break;
      case WallKind::kNoSlip: v.setZero(); break;
    }
  }
  std::array<WallKind, 4> kinds_;
  std::vector<char> rigid_layer_;  // per grid field: a rigid body's (prescribed, not recorded)
  std::vector<std::array<std::vector<char>, 4>> held_;  // per layer, per side, per control point
};

}  // namespace bsmpm

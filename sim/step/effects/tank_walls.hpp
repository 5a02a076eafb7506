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
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>&) {
    return std::make_unique<TankWalls>(p.kinds);
  }

  explicit TankWalls(std::array<WallKind, 4> kinds) : kinds_(kinds) {}

  std::string describe() const override {
    std::string s = "tank walls:";
    for (int side = 0; side < 4; ++side)
      s += std::string(" ") + wall_side_name(side) + " " + wall_kind_name(kinds_[side]);
    return s;
  }

  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override {
    const int nx = st.grid.nx(), ny = st.grid.ny();
    held_.resize(st.layers.size());
    for (std::size_t l = 0; l < st.layers.size(); ++l) {
      GridLayer& layer = st.layers[l];
      if (layer.active.empty()) continue;
      auto& v = phase_velocity(layer, phase);
      auto& held = held_[l];
      held[kLeft].resize(ny); held[kRight].resize(ny); held[kBottom].resize(nx); held[kTop].resize(nx);
      const NodeBox& b = layer.active;
      const bool update = phase == VelocityPhase::kUpdate;
      if (b.i0 == 0) for (int j = b.j0; j < b.j1; ++j) apply(v[j], kLeft, 0, -1.0, held[kLeft][j], update);
      if (b.i1 == nx)
        for (int j = b.j0; j < b.j1; ++j) apply(v[(nx - 1) * ny + j], kRight, 0, 1.0, held[kRight][j], update);
      if (b.j0 == 0) for (int i = b.i0; i < b.i1; ++i) apply(v[i * ny], kBottom, 1, -1.0, held[kBottom][i], update);
      if (b.j1 == ny) for (int i = b.i0; i < b.i1; ++i) apply(v[i * ny + ny - 1], kTop, 1, 1.0, held[kTop][i], update);
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
  std::vector<std::array<std::vector<char>, 4>> held_;  // per layer, per side, per control point
};

}  // namespace bsmpm

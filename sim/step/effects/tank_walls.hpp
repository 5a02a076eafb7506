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
// `skin_friction` C_f adds a wall shear to fluids on the slip walls: the traction
// tau = rho0 C_f |v_t| v_t against the tangential velocity v_t at the wall, the quadratic
// law of turbulent wall friction, as a boundary term of the weak form (docs/method.md §3).
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/boundaries.hpp"
#include "core/format.hpp"
#include "step/effects/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// [domain.walls] left, right, bottom, top = "slip" (default), "symmetry" or "no_slip";
// skin_friction = C_f >= 0 (default 0: free slip, the paper).
struct TankWallParameters {
  std::array<WallKind, 4> kinds{WallKind::kSlip, WallKind::kSlip, WallKind::kSlip, WallKind::kSlip};
  double skin_friction = 0.0;

  // Every scene has the tank's walls.
  static std::optional<TankWallParameters> read(SceneTables& scene) {
    TankWallParameters p;
    if (auto walls = scene.domain.optional_table("walls")) {
      for (int side = 0; side < 4; ++side) {
        const std::string kind = walls->choice_or(wall_side_name(side), "slip", {"slip", "symmetry", "no_slip"});
        p.kinds[side] = kind == "slip" ? WallKind::kSlip : kind == "symmetry" ? WallKind::kSymmetry : WallKind::kNoSlip;
      }
      p.skin_friction = walls->number_or("skin_friction", 0.0, Range::non_negative());
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
    std::vector<double> fluid_density(st.layers.size(), 0.0);
    for (const Body& b : st.bodies) {
      if (is_rigid(b.material)) rigid[b.layer] = 1;
      if (is_fluid(b.material)) fluid_density[b.layer] = density_of(b.material);
    }
    return std::make_unique<TankWalls>(p.kinds, std::move(rigid), p.skin_friction, std::move(fluid_density));
  }

  TankWalls(std::array<WallKind, 4> kinds, std::vector<char> rigid_layer = {}, double skin_friction = 0.0,
            std::vector<double> fluid_density = {})
      : kinds_(kinds), skin_friction_(skin_friction), fluid_density_(std::move(fluid_density)),
        rigid_layer_(std::move(rigid_layer)) {}

  std::string describe() const override {
    std::string s = "tank walls:";
    for (int side = 0; side < 4; ++side)
      s += std::string(" ") + wall_side_name(side) + " " + wall_kind_name(kinds_[side]);
    if (skin_friction_ > 0.0) s += format(", skin friction C_f = %g on fluids", skin_friction_);
    return s;
  }

  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override {
    const int nx = st.grid.nx(), ny = st.grid.ny();
    const bool update = phase == VelocityPhase::kUpdate;
    auto& impulse = st.diagnostics.wall_impulse;
    if (update) {
      // With a value: Eigen's default constructor leaves a Vec2 uninitialised, and the
      // first step of a resumed run gets memory the checkpoint's reading left behind.
      for (const int side : {kLeft, kRight}) impulse[side].resize(ny, Vec2::Zero());
      for (const int side : {kBottom, kTop}) impulse[side].resize(nx, Vec2::Zero());
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
      // Skin friction is a force: it acts in the update phase, on a fluid's field only.
      const double shear = update && l < fluid_density_.size() ? skin_friction_ * fluid_density_[l] * st.dt : 0.0;
      auto hold = [&](int n, int side, int axis, double outward, int k) {
        const Vec2 before = v[n];
        apply(v[n], side, axis, outward, held[side][k], update);
        const double m = layer.mass[n];
        if (!(m > st.mass_cutoff)) return;  // a node this light carries no velocity
        if (shear > 0.0 && kinds_[side] == WallKind::kSlip) {
          // docs/method.md §3, eq. W1: m_I dv_t/dt = -rho0 C_f |v_t| v_t L_I, with L_I the
          // integral of the control point's basis along the wall; integrated exactly over
          // the step, so it slows v_t and never reverses it.
          const double length = axis == 0 ? st.grid.by.integral(k) : st.grid.bx.integral(k);
          double& vt = v[n][1 - axis];
          vt /= 1.0 + shear * length / m * std::abs(vt);
        }
        if (!record) return;
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
  double skin_friction_ = 0.0;
  std::vector<double> fluid_density_;  // per grid field: rho0 of a fluid, 0 otherwise
  std::vector<char> rigid_layer_;  // per grid field: a rigid body's (prescribed, not recorded)
  std::vector<std::array<std::vector<char>, 4>> held_;  // per layer, per side, per control point
};

}  // namespace bsmpm

// Multi-body contact on the shared control-point grid of BSMPM.
//
// Li L.H., Lian Y.P., Li M.J., et al. (2024), A contact method for B-spline material point
// method with application in impact and penetration problems, Comput. Mech. 73:1351-1369;
// as used by Hua et al. (2025), Section 2.2, eqs. 15-35; docs/method.md §6.
//
// Every body in contact keeps its own grid field (GridLayer). At a control point where two
// bodies r and s both have mass:
//  - normals from each body's mass gradient, n^b = g^b / |g^b| with g^b = sum_p m_p grad S_Ip
//    (grad S_I at the particles points from them towards the control point, so g^b is the
//    body's outward direction there), made collinear:
//    n^r = (n^r - n^s) / |n^r - n^s|, n^s = -n^r (a rigid body's own normal when one is rigid);
//  - detection by approach, (v^r - v^s) . n^r > 0 (eqs. 16-17), AND by physical distance:
//    near the control point each body is the cloud of its particles in the point's support,
//    each particle a cell of the body's particle spacing. The gap between the two clouds is
//    measured along n^r and along the grid axes (separating axes: where a corner tilts n^r,
//    the axes still see the gap), and the bodies are in contact at the point only when the
//    gap along every one of these axes closes within this step. Without the distance test
//    the wide B-spline support makes bodies exchange forces while still apart;
//  - the Lagrange-multiplier force that makes the velocities equal (eq. 33),
//    f^r = -f^s = m^r m^s / ((m^r + m^s) dt) (v^s - v^r), split into normal and tangential
//    parts (eq. 34), the tangential part capped at mu |f_nor| (Coulomb, eq. 35) or dropped
//    (frictionless); "stick" keeps all of it at every shared control point (single field);
//  - the same correction on the remapped velocities of eq. 13, at the control points found
//    in contact, so the strain increment sees it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_parameters.hpp"
#include "core/boundaries.hpp"
#include "core/format.hpp"
#include "step/effect.hpp"

namespace bsmpm {

template <int P>
class LiLian2024Contact final : public EffectBase<LiLian2024Contact<P>, P> {
 public:
  using Parameters = ContactParameters;
  // After the prescribed motion of rigid bodies, which it must see; before the walls.
  static constexpr EffectPhase kPhase = EffectPhase::kContact;
  // The pairs whose bodies have fields of their own; absent when there is none (a "stick"
  // pair of deformable bodies shares one field: that is a single field, no contact).
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>& st);

  LiLian2024Contact(std::vector<ContactPair> pairs, std::vector<std::string> body_names)
      : pairs_(std::move(pairs)), body_names_(std::move(body_names)), state_(pairs_.size()) {}

  std::string describe() const override;
  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override;

 private:
  // Extent of one body's particle cloud near a control point, along the separating axes:
  // n^r, +x, -x, +y, -y (largest x.a + half spacing for r; smallest x.a - half spacing for s).
  static constexpr int kAxes = 5;
  using Extent = std::array<double, kAxes>;

  struct PairState {
    std::vector<int> nodes;      // control points where both bodies have mass
    std::vector<Vec2> normal;    // n^r at each of them
    std::vector<Extent> reach_r, reach_s;  // detection
    std::vector<char> active;    // in contact this step
  };
  static Vec2 axis(const Vec2& normal, int a) {
    switch (a) {
      case 0: return normal;
      case 1: return {1.0, 0.0};
      case 2: return {-1.0, 0.0};
      case 3: return {0.0, 1.0};
      default: return {0.0, -1.0};
    }
  }

  void find_shared_nodes(StepState<P>& st, const ContactPair& pair, PairState& ps) const;
  void measure_surfaces(StepState<P>& st, const ContactPair& pair, PairState& ps);
  void correct(StepState<P>& st, const ContactPair& pair, PairState& ps, VelocityPhase phase, std::size_t k) const;

  std::vector<ContactPair> pairs_;
  std::vector<std::string> body_names_;  // for describe()
  std::vector<PairState> state_;
  std::vector<int> slot_;  // control point -> index in PairState::nodes, or -1
};

template <int P>
std::unique_ptr<Effect<P>> LiLian2024Contact<P>::create(const Parameters& p, const StepState<P>& st) {
  std::vector<ContactPair> pairs;
  for (const ContactPair& c : p.pairs)
    if (st.bodies[c.body_r].layer != st.bodies[c.body_s].layer) pairs.push_back(c);
  if (pairs.empty()) return nullptr;
  std::vector<std::string> names;
  for (const Body& b : st.bodies) names.push_back(b.name);
  return std::make_unique<LiLian2024Contact>(std::move(pairs), std::move(names));
}

template <int P>
std::string LiLian2024Contact<P>::describe() const {
  std::string s = "contact (Li, Lian et al. 2024):";
  for (const auto& p : pairs_) {
    const std::string kind = p.kind == ContactKind::kCoulomb ? format("Coulomb mu = %g", p.friction)
                             : p.kind == ContactKind::kFrictionless ? "frictionless"
                                                                     : "stick";
    s += format(" [%s-%s %s%s]", body_names_[p.body_r].c_str(), body_names_[p.body_s].c_str(), kind.c_str(),
                p.kind != ContactKind::kStick && !p.distance_check ? ", approach only" : "");
  }
  return s;
}

template <int P>
void LiLian2024Contact<P>::constrain_velocity(StepState<P>& st, VelocityPhase phase) {
  if (phase == VelocityPhase::kUpdate) st.diagnostics.contact.resize(pairs_.size());
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const ContactPair& pair = pairs_[k];
    PairState& ps = state_[k];
    if (phase == VelocityPhase::kUpdate) {
      find_shared_nodes(st, pair, ps);
      if (pair.kind != ContactKind::kStick && pair.distance_check && !ps.nodes.empty()) measure_surfaces(st, pair, ps);
    }
    correct(st, pair, ps, phase, k);
  }
}

template <int P>
void LiLian2024Contact<P>::find_shared_nodes(StepState<P>& st, const ContactPair& pair, PairState& ps) const {
  const Body& r = st.bodies[pair.body_r];
  const Body& s = st.bodies[pair.body_s];
  const GridLayer& Lr = st.layers[r.layer];
  const GridLayer& Ls = st.layers[s.layer];
  ps.nodes.clear();
  ps.normal.clear();
  const NodeBox& a = Lr.active;
  const NodeBox& b = Ls.active;
  const NodeBox box{std::max(a.i0, b.i0), std::min(a.i1, b.i1), std::max(a.j0, b.j0), std::min(a.j1, b.j1)};
  if (box.empty()) return;
  const bool rigid_r = is_rigid(r.material), rigid_s = is_rigid(s.material);
  for_each_node(box, st.grid.ny(), [&](int n, int, int) {
    if (!(Lr.mass[n] > st.mass_cutoff && Ls.mass[n] > st.mass_cutoff)) return;
    const double gr = Lr.mass_gradient[n].norm(), gs = Ls.mass_gradient[n].norm();
    Vec2 normal;
    if (rigid_s && gs > 0.0) normal = -Ls.mass_gradient[n] / gs;      // -n^s of the rigid body
    else if (rigid_r && gr > 0.0) normal = Lr.mass_gradient[n] / gr;  // n^r of the rigid body
    else {
      Vec2 sum = Vec2::Zero();  // n^r - n^s
      if (gr > 0.0) sum += Lr.mass_gradient[n] / gr;
      if (gs > 0.0) sum -= Ls.mass_gradient[n] / gs;
      const double len = sum.norm();
      if (len < 1e-12) return;  // no direction to push along
      normal = sum / len;
    }
    ps.nodes.push_back(n);
    ps.normal.push_back(normal);
  });
  ps.active.assign(ps.nodes.size(), 1);
}

// For every shared control point: how far each body's particles in its support reach
// along the separating axes, each particle extended by half its spacing.
template <int P>
void LiLian2024Contact<P>::measure_surfaces(StepState<P>& st, const ContactPair& pair, PairState& ps) {
  const std::size_t count = ps.nodes.size();
  slot_.resize(st.grid.node_count(), -1);
  for (std::size_t k = 0; k < count; ++k) slot_[ps.nodes[k]] = static_cast<int>(k);
  Extent lowest, highest;
  lowest.fill(-std::numeric_limits<double>::infinity());
  highest.fill(std::numeric_limits<double>::infinity());
  ps.reach_r.assign(count, lowest);   // r: largest x.a + half
  ps.reach_s.assign(count, highest);  // s: smallest x.a - half
  const int ny = st.grid.ny();
  for (int side = 0; side < 2; ++side) {
    const int b = side == 0 ? pair.body_r : pair.body_s;
    const Vec2 spacing = st.bodies[b].spacing;
    std::vector<Extent>& reach = side == 0 ? ps.reach_r : ps.reach_s;
    st.schedules[b].for_each([&](std::uint32_t p) {
      const auto& w = st.weights[p];
      const Vec2& x = st.particles.x[p];
      for (int a = 0; a <= P; ++a)
        for (int c = 0; c <= P; ++c) {
          const int k = slot_[(w.i0 + a) * ny + w.j0 + c];
          if (k < 0) continue;
          for (int ax = 0; ax < kAxes; ++ax) {
            const Vec2 dir = axis(ps.normal[k], ax);
            const double half = 0.5 * (std::abs(dir.x()) * spacing.x() + std::abs(dir.y()) * spacing.y());
            const double along = x.dot(dir);
            if (side == 0) reach[k][ax] = std::max(reach[k][ax], along + half);
            else reach[k][ax] = std::min(reach[k][ax], along - half);
          }
        }
    });
  }
  for (int n : ps.nodes) slot_[n] = -1;
}

template <int P>
void LiLian2024Contact<P>::correct(StepState<P>& st, const ContactPair& pair, PairState& ps, VelocityPhase phase,
                                   std::size_t pair_index) const {
  const Body& r = st.bodies[pair.body_r];
  const Body& s = st.bodies[pair.body_s];
  GridLayer& Lr = st.layers[r.layer];
  GridLayer& Ls = st.layers[s.layer];
  auto& vr_field = phase_velocity(Lr, phase);
  auto& vs_field = phase_velocity(Ls, phase);
  const bool rigid_r = is_rigid(r.material), rigid_s = is_rigid(s.material);
  const bool update = phase == VelocityPhase::kUpdate;
  const double dt = st.dt;
  const bool use_distance = pair.kind != ContactKind::kStick && pair.distance_check && update;
  for (std::size_t k = 0; k < ps.nodes.size(); ++k) {
    if (!ps.active[k]) continue;
    const int n = ps.nodes[k];
    const Vec2& normal = ps.normal[k];
    Vec2& vr = vr_field[n];
    Vec2& vs = vs_field[n];
    const double approach = (vr - vs).dot(normal);  // eq. 17
    if (pair.kind != ContactKind::kStick) {
      bool touching = approach > 0.0;
      // The distance criterion: no separating axis keeps a gap open through this step.
      for (int ax = 0; touching && use_distance && ax < kAxes; ++ax) {
        const Vec2 dir = axis(normal, ax);
        const double gap = ps.reach_s[k][ax] - ps.reach_r[k][ax];
        touching = gap - dt * (vr - vs).dot(dir) <= 0.0;
      }
      if (update) ps.active[k] = touching;
      if (!touching) continue;
    }
    // Impulse on r of the Lagrange multiplier that equalises the velocities (eq. 33 times
    // dt): the reduced mass m^r m^s / (m^r + m^s), or the other body's mass when one is rigid.
    const double mr = Lr.mass[n], ms = Ls.mass[n];
    const double reduced = rigid_s ? mr : rigid_r ? ms : mr * ms / (mr + ms);
    Vec2 impulse = reduced * (vs - vr);
    if (pair.kind != ContactKind::kStick) {
      const Vec2 normal_part = impulse.dot(normal) * normal;  // eq. 34
      Vec2 tangential = impulse - normal_part;
      if (pair.kind == ContactKind::kFrictionless) {
        tangential.setZero();
      } else {
        const double cap = pair.friction * normal_part.norm();  // eq. 35
        const double t = tangential.norm();
        if (t > cap) tangential *= cap / t;
      }
      impulse = normal_part + tangential;
    }
    // f^r = -f^s: momentum is exchanged, not created.
    const Vec2 vr_before = vr, vs_before = vs;
    if (!rigid_r) vr += impulse / mr;
    if (!rigid_s) vs -= impulse / ms;
    if (update) {
      StepDiagnostics& d = st.diagnostics;
      d.contact_impulse += impulse.norm();
      ++d.contact_nodes;
      d.contact[pair_index].nodes.push_back(n);
      d.contact[pair_index].impulse.push_back(impulse);
      // Between deformable bodies: the nodal kinetic energy the contact takes (StepDiagnostics::
      // work). A rigid body moving at v_R does the work of its push, impulse . v_R dt / dt.
      if (rigid_s) d.work.rigid_contact += impulse.dot(vs);
      else if (rigid_r) d.work.rigid_contact -= impulse.dot(vr);
      else d.work.contact += 0.5 * mr * (vr.squaredNorm() - vr_before.squaredNorm()) +
                             0.5 * ms * (vs.squaredNorm() - vs_before.squaredNorm());
    }
  }
}

}  // namespace bsmpm

// Clamped parts of a body (e.g. the elastic gate's base fixed to the floor): the body's
// velocity field is held at zero on each clamp region. The control points whose basis
// functions are non-zero anywhere on the region are set to zero, so the interpolated
// velocity vanishes on the whole region, in both the update and the remap.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "step/effects/scene_tables.hpp"
#include "step/effect.hpp"

namespace bsmpm {

// [[bodies.clamp]] min = [x, y], max = [x, y] under a body: a region of it held at rest.
struct ClampParameters {
  struct Region {
    int body;
    Rectangle box;
  };
  std::vector<Region> regions;

  static std::optional<ClampParameters> read(SceneTables& scene) {
    ClampParameters p;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      BodyTable& body = scene.bodies[b];
      auto clamps = body.table.tables("clamp");
      for (auto& c : clamps) {
        p.regions.push_back({static_cast<int>(b), read_region(c, body.shape, scene.domain_box)});
        c.finish();
      }
      if (!clamps.empty() && is_rigid(body.material))
        body.table.fail("clamp", "a rigid body's motion is prescribed already");
    }
    if (p.regions.empty()) return std::nullopt;
    return p;
  }

  // A region may be a segment or a point (max == min along an axis); it must lie in the
  // domain and touch its body (a region beside the body would clamp nothing, or another body).
  static Rectangle read_region(TableReader& t, const Shape& body, const Rectangle& domain) {
    Rectangle r{t.vec2("min"), t.vec2("max")};
    if (!(r.max.x() >= r.min.x() && r.max.y() >= r.min.y())) t.fail("max", "must not be below min in x or y");
    if (extends_outside(r, domain)) t.fail("min", "the region extends outside the domain");
    const double tol = domain_tolerance(domain);
    const Rectangle box = bounding_box(body);
    if ((r.max.array() < box.min.array() - tol).any() || (r.min.array() > box.max.array() + tol).any())
      t.fail("min", "the region does not touch its body's shape");
    return r;
  }
};

template <int P>
class ClampedNodes final : public EffectBase<ClampedNodes<P>, P> {
 public:
  using Parameters = ClampParameters;
  static constexpr EffectPhase kPhase = EffectPhase::kClamps;
  struct Clamp {
    std::string body;
    int layer;
    Vec2 min, max;
    std::vector<int> nodes;
  };
  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>& st) {
    std::vector<Clamp> clamps;
    for (const auto& r : p.regions)
      clamps.push_back({st.bodies[r.body].name, st.bodies[r.body].layer, r.box.min, r.box.max, {}});
    return std::make_unique<ClampedNodes>(st.grid, std::move(clamps));
  }

  ClampedNodes(const Grid<P>& grid, std::vector<Clamp> clamps) : clamps_(std::move(clamps)) {
    for (auto& c : clamps_) {
      const auto [i0, i1] = grid.bx.support_range(c.min.x(), c.max.x());
      const auto [j0, j1] = grid.by.support_range(c.min.y(), c.max.y());
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) c.nodes.push_back(grid.index(i, j));
    }
  }

  std::string describe() const override {
    std::string s = "clamps:";
    for (const auto& c : clamps_)
      s += format(" %s on [%g, %g] x [%g, %g] m (%zu control points)", c.body.c_str(), c.min.x(), c.max.x(), c.min.y(),
                  c.max.y(), c.nodes.size());
    return s;
  }
  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override {
    for (const auto& c : clamps_) {
      GridLayer& layer = st.layers[c.layer];
      auto& v = phase_velocity(layer, phase);
      for (int n : c.nodes) {
        // The clamp takes the kinetic energy of its control points (StepDiagnostics::work).
        if (phase == VelocityPhase::kUpdate && layer.mass[n] > st.mass_cutoff)
          st.diagnostics.work.clamps -= 0.5 * layer.mass[n] * v[n].squaredNorm();
        v[n].setZero();
      }
    }
  }

 private:
  std::vector<Clamp> clamps_;
};

}  // namespace bsmpm

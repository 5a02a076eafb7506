// Clamped parts of a body (e.g. the elastic gate's base fixed to the floor): the body's
// velocity field is held at zero on each clamp region. The control points whose basis
// functions are non-zero anywhere on the region are set to zero, so the interpolated
// velocity vanishes on the whole region, in both the update and the remap.
#pragma once

#include <string>
#include <vector>

#include "core/format.hpp"
#include "step/effect.hpp"

namespace bsmpm {

template <int P>
class ClampedNodes final : public Effect<P> {
 public:
  struct Clamp {
    std::string body;
    int layer;
    Vec2 min, max;
    std::vector<int> nodes;
  };

  ClampedNodes(const Grid<P>& grid, std::vector<Clamp> clamps) : clamps_(std::move(clamps)) {
    for (auto& c : clamps_) {
      const auto [i0, i1] = grid.bx.support_range(c.min.x(), c.max.x());
      const auto [j0, j1] = grid.by.support_range(c.min.y(), c.max.y());
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) c.nodes.push_back(grid.index(i, j));
    }
  }

  unsigned hooks() const override { return kHookConstrainVelocity; }
  std::string describe() const override {
    std::string s = "clamps:";
    for (const auto& c : clamps_)
      s += format(" %s on [%g, %g] x [%g, %g] m (%zu control points)", c.body.c_str(), c.min.x(), c.max.x(), c.min.y(),
                  c.max.y(), c.nodes.size());
    return s;
  }
  void constrain_velocity(StepState<P>& st, VelocityPhase phase) override {
    for (const auto& c : clamps_) {
      auto& v = phase_velocity(st.layers[c.layer], phase);
      for (int n : c.nodes) v[n].setZero();
    }
  }
  const std::vector<Clamp>& clamps() const { return clamps_; }

 private:
  std::vector<Clamp> clamps_;
};

}  // namespace bsmpm

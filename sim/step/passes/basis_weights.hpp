// Step 1 of docs/method.md §2: the basis at each particle, and per body its scatter schedule
// and the box of control points it touches.
#pragma once

#include <algorithm>
#include <vector>

#include "step/step_state.hpp"

namespace bsmpm {

// One parallel pass per body: the box as exact min/max reductions (the same for any thread
// count), the first columns copied into a compact array from which the serial schedule build
// reads 4 bytes a particle instead of striding through the weights.
template <int P>
class BasisWeights {
 public:
  void compute(StepState<P>& st) {
    const PhaseScope timed(st.timer, StepPhase::kWeights);
    auto& ps = st.particles;
    column_.resize(ps.size());
    st.weights.resize(ps.size());
    for (auto& layer : st.layers) layer.active = NodeBox{};
    for (std::size_t b = 0; b < st.bodies.size(); ++b) {
      const Body& body = st.bodies[b];
      const long begin = static_cast<long>(body.begin), end = static_cast<long>(body.end);
      int i0 = st.grid.nx(), i1 = 0, j0 = st.grid.ny(), j1 = 0;
#pragma omp parallel for schedule(static) reduction(min : i0, j0) reduction(max : i1, j1)
      for (long p = begin; p < end; ++p) {
        auto& w = st.weights[p];
        w.i0 = st.grid.bx.evaluate(ps.x[p].x(), w.wx, w.gx);
        w.j0 = st.grid.by.evaluate(ps.x[p].y(), w.wy, w.gy);
        column_[p] = w.i0;
        i0 = std::min(i0, w.i0);
        i1 = std::max(i1, w.i0);
        j0 = std::min(j0, w.j0);
        j1 = std::max(j1, w.j0);
      }
      st.schedules[b].build(body.begin, body.end, st.grid.nx(), [&](std::size_t p) { return column_[p]; });
      if (body.size() == 0) continue;
      st.layers[body.layer].active.include(NodeBox{i0, i1 + P + 1, j0, j1 + P + 1});
    }
  }

  std::size_t bytes() const { return heap_bytes(column_); }

 private:
  std::vector<int> column_;  // each particle's first column, for the schedule build
};

}  // namespace bsmpm

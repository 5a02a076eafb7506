// Particles of each body sorted by cell (x-major, like the control points), so that the
// scatter and gather walk the grid in order (docs/architecture.md, data layout).
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

#include "step/step_state.hpp"

namespace bsmpm {

class ParticleSort {
 public:
  // A counting sort: stable (the order a stable comparison sort gives), linear in the
  // particles and cells, and into buffers kept from one sort to the next, so that it
  // allocates nothing after the first. index_of_id follows the particles.
  template <int P>
  void sort(StepState<P>& st) {
    const PhaseScope timed(st.timer, StepPhase::kSort);
    auto& ps = st.particles;
    const int cy = st.grid.by.cells();
    const std::size_t cells = std::size_t(st.grid.bx.cells()) * cy;
    for (const Body& b : st.bodies) {
      const std::size_t n = b.size();
      key_.resize(n);
      order_.resize(n);
      start_.assign(cells + 1, 0);
      for (std::size_t k = 0; k < n; ++k) {
        const Vec2& x = ps.x[b.begin + k];
        key_[k] = std::uint32_t(st.grid.bx.cell_of(x.x())) * cy + st.grid.by.cell_of(x.y());
        ++start_[key_[k] + 1];
      }
      std::partial_sum(start_.begin(), start_.end(), start_.begin());
      for (std::size_t k = 0; k < n; ++k) order_[start_[key_[k]]++] = static_cast<std::uint32_t>(k);
      ps.permute(b.begin, order_, scratch_);
    }
    for (std::size_t p = 0; p < ps.size(); ++p) st.index_of_id[ps.id[p]] = static_cast<std::uint32_t>(p);
  }

  std::size_t particle_bytes() const { return heap_bytes(key_) + heap_bytes(order_) + scratch_.bytes(); }
  std::size_t cell_bytes() const { return heap_bytes(start_); }

 private:
  std::vector<std::uint32_t> key_, order_, start_;
  Particles::PermuteScratch scratch_;
};

}  // namespace bsmpm

// Deterministic parallel scatter to the grid (house style: same bits whatever the thread
// count). Particles are binned into vertical strips of kStripWidth cells by their first
// control-point column; a particle writes to columns [i0, i0 + P], so strips two apart never
// share a control point. Even strips run in parallel, then odd ones; every control point
// therefore receives its contributions in the same order for any number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include <omp.h>

#include "core/types.hpp"

namespace bsmpm {

class StripSchedule {
 public:
  static constexpr int kStripWidth = 8;  // >= P, so strips s and s+2 never overlap

  // Bins the particles [begin, end) by column (first control point in x).
  template <class ColumnOf>
  void build(std::size_t begin, std::size_t end, int columns, ColumnOf&& column_of) {
    strips_ = columns / kStripWidth + 1;
    offsets_.assign(strips_ + 1, 0);
    order_.resize(end - begin);
    for (std::size_t p = begin; p < end; ++p) ++offsets_[column_of(p) / kStripWidth + 1];
    for (int s = 0; s < strips_; ++s) offsets_[s + 1] += offsets_[s];
    fill_.assign(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t p = begin; p < end; ++p)
      order_[fill_[column_of(p) / kStripWidth]++] = static_cast<std::uint32_t>(p);
  }

  std::size_t bytes() const { return heap_bytes(offsets_) + heap_bytes(fill_) + heap_bytes(order_); }

  // Calls f(p) for every particle; no two concurrent calls touch the same control point.
  template <class F>
  void for_each(F&& f) const {
    const bool parallel = order_.size() > 2048;
    for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1) if (parallel)
      for (int s = colour; s < strips_; s += 2)
        for (std::uint32_t k = offsets_[s]; k < offsets_[s + 1]; ++k) f(order_[k]);
    }
  }

 private:
  int strips_ = 0;
  std::vector<std::uint32_t> offsets_, fill_, order_;
};

}  // namespace bsmpm

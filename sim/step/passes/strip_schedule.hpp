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

  // Bins the particles [begin, end) by column (first control point in x), in ascending
  // order within each strip. Each thread counts and places a contiguous block of the
  // particles, the blocks in order: the schedule is the same for any thread count.
  template <class ColumnOf>
  void build(std::size_t begin, std::size_t end, int columns, ColumnOf&& column_of) {
    strips_ = columns / kStripWidth + 1;
    order_.resize(end - begin);
    const std::size_t n = end - begin;
    const int blocks = n > 4096 ? omp_get_max_threads() : 1;
    counts_.assign(std::size_t(blocks) * strips_, 0);
    offsets_.assign(strips_ + 1, 0);
#pragma omp parallel num_threads(blocks) if (blocks > 1)
    {
      const int t = omp_get_thread_num();
      const std::size_t first = begin + n * t / blocks, last = begin + n * (t + 1) / blocks;
      std::uint32_t* const count = counts_.data() + std::size_t(t) * strips_;
      for (std::size_t p = first; p < last; ++p) ++count[column_of(p) / kStripWidth];
#pragma omp barrier
#pragma omp single
      {
        // Strip s holds block 0's particles of s, then block 1's, ...: where each block starts.
        std::uint32_t at = 0;
        for (int s = 0; s < strips_; ++s) {
          offsets_[s] = at;
          for (int b = 0; b < blocks; ++b) {
            const std::uint32_t c = counts_[std::size_t(b) * strips_ + s];
            counts_[std::size_t(b) * strips_ + s] = at;
            at += c;
          }
        }
        offsets_[strips_] = at;
      }
      for (std::size_t p = first; p < last; ++p)
        order_[count[column_of(p) / kStripWidth]++] = static_cast<std::uint32_t>(p);
    }
  }

  std::size_t bytes() const { return heap_bytes(offsets_) + heap_bytes(counts_) + heap_bytes(order_); }

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
  std::vector<std::uint32_t> offsets_, counts_, order_;  // counts_: per block and strip
};

}  // namespace bsmpm

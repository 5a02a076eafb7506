// Which frames of a run to draw: all, by index, by time t, or by non-dimensional time
// T* = t sqrt(g/H) (the paper's figures are at whole T*). A time picks the nearest frame.
#pragma once

#include <vector>

#include "io/run_reader.hpp"

namespace bsmpm::render {

struct FrameSelection {
  enum class Kind { kAll, kIndices, kTimes, kTimesStar };
  Kind kind = Kind::kAll;
  std::vector<double> values;  // frame indices (negative: from the end, -1 = last), t [s] or T*
};

// Frame indices in the order asked for. Throws UsageError for an index out of range or a
// time more than half a frame interval outside the run.
std::vector<int> select_frames(const RunReader& run, const FrameSelection& selection);

}  // namespace bsmpm::render

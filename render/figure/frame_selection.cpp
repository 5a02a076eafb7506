#include "figure/frame_selection.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"

namespace bsmpm::render {

namespace {

std::string number(double x) { return format("%g", x); }

int nearest_frame(const RunReader& run, double t, const std::string& asked) {
  const auto& frames = run.frames();
  int best = 0;
  for (std::size_t k = 1; k < frames.size(); ++k)
    if (std::fabs(frames[k].time - t) < std::fabs(frames[best].time - t)) best = static_cast<int>(k);
  // Half the spacing of the frames around the run's ends; inside, the nearest frame is fine.
  const double first = frames.front().time, last = frames.back().time;
  const double spacing = frames.size() > 1 ? (last - first) / (frames.size() - 1) : 0.0;
  const double slack = 0.5 * spacing + 1e-9 * std::max(1.0, std::fabs(t));
  if (t < first - slack || t > last + slack)
    throw UsageError(asked + " is outside the run's frames (t = " + number(first) + " .. " + number(last) + " s)");
  return best;
}

}  // namespace

std::vector<int> select_frames(const RunReader& run, const FrameSelection& selection) {
  const int count = static_cast<int>(run.frames().size());
  if (count == 0) throw UsageError(run.path() + ": the run has no frames yet");
  std::vector<int> out;
  switch (selection.kind) {
    case FrameSelection::Kind::kAll:
      for (int k = 0; k < count; ++k) out.push_back(k);
      break;
    case FrameSelection::Kind::kIndices:
      for (double v : selection.values) {
        if (v != std::floor(v)) throw UsageError("frame index " + number(v) + " is not a whole number");
        const int k = v < 0 ? count + static_cast<int>(v) : static_cast<int>(v);
        if (k < 0 || k >= count)
          throw UsageError("no frame " + number(v) + ": the run has frames 0 .. " + std::to_string(count - 1));
        out.push_back(k);
      }
      break;
    case FrameSelection::Kind::kTimes:
      for (double t : selection.values) out.push_back(nearest_frame(run, t, "t = " + number(t) + " s"));
      break;
    case FrameSelection::Kind::kTimesStar: {
      const double factor = run.reference().time_factor();
      for (double ts : selection.values) out.push_back(nearest_frame(run, ts / factor, "T* = " + number(ts)));
      break;
    }
  }
  return out;
}

}  // namespace bsmpm::render

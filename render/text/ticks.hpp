// Tick values and labels for colour bars: "nice" steps of 1, 2 or 5 times a power of ten
// after Heckbert, "Nice numbers for graph labels", Graphics Gems (1990), with the ticks
// kept inside the range (tight labelling).
#pragma once

#include <string>
#include <vector>

namespace bsmpm::render {

struct Tick {
  double value = 0.0;
  std::string label;
};

// About `target` ticks covering [lo, hi], lo < hi; at least two (a finer step if needed).
std::vector<Tick> nice_ticks(double lo, double hi, int target = 5);

// `value` with `decimals` digits after the point; negatives take a typographic minus
// (U+2212) and -0 prints as 0.
std::string format_number(double value, int decimals);

}  // namespace bsmpm::render

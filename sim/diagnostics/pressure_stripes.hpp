// The stripe number of a pressure cloud (docs/validation.md, "Pressure stripes"): how far
// each fluid particle's pressure departs from the mean of its fluid neighbours within a
// radius (2 h), as an RMS over the particles in a band. A smooth field gives nearly zero
// (a linear one exactly, away from the free surface and the walls); a field that alternates
// from one particle column to the next gives about the alternation's amplitude.
#pragma once

#include <cstddef>
#include <vector>

#include "core/types.hpp"

namespace bsmpm {

// The particles measured: those whose position lies in [x_min, x_max] x [y_min, y_max].
struct StripeBand {
  double x_min = -1.0e300, x_max = 1.0e300;
  double y_min = 0.0, y_max = 0.0;
};

// Squared departures summed over the measured particles of one or more frames.
struct StripeSum {
  double sum_squares = 0.0;  // Pa^2
  std::size_t count = 0;     // particles measured (those with at least one neighbour)

  double rms() const;        // Pa; NaN when nothing was measured
  StripeSum& operator+=(const StripeSum& o) {
    sum_squares += o.sum_squares;
    count += o.count;
    return *this;
  }
};

// One frame: positions and pressures of all particles, `measured[i]` true for the particles
// that count (the fluid's); neighbours are the other measured particles within `radius`.
// Serial, in index order: the same bits every time.
StripeSum pressure_stripes(const std::vector<Vec2>& x, const std::vector<double>& p,
                           const std::vector<char>& measured, const StripeBand& band, double radius);

}  // namespace bsmpm

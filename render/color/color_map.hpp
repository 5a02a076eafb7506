// Colour maps: value in [0, 1] -> 8-bit sRGB.
//   viridis, inferno  perceptually uniform (van der Walt & Smith, matplotlib 2.0 tables)
//   jet               the rainbow of the paper's pressure clouds (MATLAB's jet, from
//                     matplotlib's piecewise-linear control points)
// The ends are exact: at(0) and at(1) are the first and last entries of the definition.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace bsmpm::render {

class ColorMap {
 public:
  // Throws UsageError for an unknown name, listing the known ones.
  static ColorMap named(const std::string& name);
  static const std::vector<std::string>& names();

  const std::string& name() const { return name_; }
  // t is clamped to [0, 1]; a non-finite t gives kMissingValue.
  Rgb at(double t) const;

  // Colour of a particle whose value is not finite.
  static constexpr Rgb kMissingValue{128, 128, 128};

 private:
  static constexpr int kEntries = 256;
  ColorMap(std::string name, const std::array<std::array<double, 3>, kEntries>& rgb);

  std::string name_;
  std::array<std::array<double, 3>, kEntries> rgb_{};
};

}  // namespace bsmpm::render

namespace bsmpm::render {

// The values a colour map spans: min maps to at(0), max to at(1).
struct ValueRange {
  double min = 0.0, max = 1.0;
  double normalized(double v) const { return (v - min) / (max - min); }
};

}  // namespace bsmpm::render

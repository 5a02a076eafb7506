#include "color/color_map.hpp"

#include <algorithm>
#include <cmath>

#include "color/color_tables.hpp"
#include "core/error.hpp"

namespace bsmpm::render {

namespace {

// One channel of a piecewise-linear map: (x, value) control points with x from 0 to 1.
struct ControlPoint {
  double x, value;
};

double interpolate(const std::vector<ControlPoint>& points, double t) {
  for (std::size_t k = 1; k < points.size(); ++k)
    if (t <= points[k].x) {
      const ControlPoint& a = points[k - 1];
      const ControlPoint& b = points[k];
      return a.value + (b.value - a.value) * (t - a.x) / (b.x - a.x);
    }
  return points.back().value;
}

// MATLAB's jet as matplotlib defines it (matplotlib/_cm.py, _jet_data): dark blue ->
// blue -> cyan -> yellow -> red -> dark red.
std::array<std::array<double, 3>, 256> jet_table() {
  const std::vector<ControlPoint> red = {{0.0, 0.0}, {0.35, 0.0}, {0.66, 1.0}, {0.89, 1.0}, {1.0, 0.5}};
  const std::vector<ControlPoint> green = {{0.0, 0.0},   {0.125, 0.0}, {0.375, 1.0},
                                           {0.64, 1.0},  {0.91, 0.0},  {1.0, 0.0}};
  const std::vector<ControlPoint> blue = {{0.0, 0.5}, {0.11, 1.0}, {0.34, 1.0}, {0.65, 0.0}, {1.0, 0.0}};
  std::array<std::array<double, 3>, 256> table{};
  for (int k = 0; k < 256; ++k) {
    const double t = k / 255.0;
    table[k] = {interpolate(red, t), interpolate(green, t), interpolate(blue, t)};
  }
  return table;
}

std::uint8_t to_byte(double c) { return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); }

}  // namespace

const std::vector<std::string>& ColorMap::names() {
  static const std::vector<std::string> known = {"viridis", "inferno", "jet"};
  return known;
}

ColorMap ColorMap::named(const std::string& name) {
  if (name == "viridis") return ColorMap(name, kViridisTable);
  if (name == "inferno") return ColorMap(name, kInfernoTable);
  if (name == "jet") return ColorMap(name, jet_table());
  std::string known;
  for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("unknown colour map '" + name + "' (known: " + known + ")");
}

ColorMap::ColorMap(std::string name, const std::array<std::array<double, 3>, kEntries>& rgb)
    : name_(std::move(name)), rgb_(rgb) {}

Rgb ColorMap::at(double t) const {
  if (!std::isfinite(t)) return kMissingValue;
  // Linear interpolation between the 256 entries, as matplotlib's LinearSegmentedColormap
  // does between control points; at 0 and 1 this returns the first and last entry exactly.
  const double s = std::clamp(t, 0.0, 1.0) * (kEntries - 1);
  const int k = std::min(static_cast<int>(s), kEntries - 2);
  const double f = s - k;
  std::array<double, 3> c{};
  for (int i = 0; i < 3; ++i) c[i] = (1.0 - f) * rgb_[k][i] + f * rgb_[k + 1][i];  // exact at f = 0, 1
  return {to_byte(c[0]), to_byte(c[1]), to_byte(c[2])};
}

}  // namespace bsmpm::render

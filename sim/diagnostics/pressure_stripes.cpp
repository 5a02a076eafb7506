#include "diagnostics/pressure_stripes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bsmpm {

double StripeSum::rms() const {
  return count == 0 ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(sum_squares / static_cast<double>(count));
}

StripeSum pressure_stripes(const std::vector<Vec2>& x, const std::vector<double>& p,
                           const std::vector<char>& measured, const StripeBand& band, double radius) {
  // Candidates: measured particles within `radius` of the band (the band's particles and
  // their neighbours), bucketed in square cells of side `radius`.
  const double lo_x = band.x_min - radius, hi_x = band.x_max + radius;
  const double lo_y = band.y_min - radius, hi_y = band.y_max + radius;
  std::vector<std::size_t> candidates;
  double min_x = std::numeric_limits<double>::infinity(), max_x = -min_x;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (measured[i] && x[i].x() >= lo_x && x[i].x() <= hi_x && x[i].y() >= lo_y && x[i].y() <= hi_y) {
      candidates.push_back(i);
      min_x = std::min(min_x, x[i].x());
      max_x = std::max(max_x, x[i].x());
    }
  StripeSum out;
  if (candidates.empty()) return out;
  const long nx = static_cast<long>((max_x - min_x) / radius) + 1;
  const long ny = static_cast<long>((hi_y - lo_y) / radius) + 1;
  auto cell_of = [&](const Vec2& q) {
    const long cx = std::clamp(static_cast<long>((q.x() - min_x) / radius), 0L, nx - 1);
    const long cy = std::clamp(static_cast<long>((q.y() - lo_y) / radius), 0L, ny - 1);
    return cy * nx + cx;
  };
  // Counting sort of the candidates by cell.
  std::vector<std::size_t> start(static_cast<std::size_t>(nx * ny) + 1, 0), sorted(candidates.size());
  for (std::size_t i : candidates) ++start[static_cast<std::size_t>(cell_of(x[i])) + 1];
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i : candidates) sorted[fill[static_cast<std::size_t>(cell_of(x[i]))]++] = i;

  const double r2 = radius * radius;
  for (std::size_t i : candidates) {
    const Vec2& xi = x[i];
    if (xi.x() < band.x_min || xi.x() > band.x_max || xi.y() < band.y_min || xi.y() > band.y_max) continue;
    const long c = cell_of(xi), cx = c % nx, cy = c / nx;
    double sum = 0.0;
    std::size_t n = 0;
    for (long by = std::max(cy - 1, 0L); by <= std::min(cy + 1, ny - 1); ++by)
      for (long bx = std::max(cx - 1, 0L); bx <= std::min(cx + 1, nx - 1); ++bx) {
        const auto b = static_cast<std::size_t>(by * nx + bx);
        for (std::size_t k = start[b]; k < start[b + 1]; ++k) {
          const std::size_t j = sorted[k];
          if (j != i && (x[j] - xi).squaredNorm() <= r2) {
            sum += p[j];
            ++n;
          }
        }
      }
    if (n == 0) continue;  // a lone particle: no neighbourhood to compare with
    const double d = p[i] - sum / static_cast<double>(n);
    out.sum_squares += d * d;
    ++out.count;
  }
  return out;
}

}  // namespace bsmpm

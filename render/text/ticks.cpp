#include "text/ticks.hpp"

#include <algorithm>
#include <cmath>

#include "core/format.hpp"

namespace bsmpm::render {

namespace {

// Heckbert's nicenum: a number of the form {1, 2, 5} x 10^k close to x (rounded or above).
double nice_number(double x, bool round) {
  const double exponent = std::floor(std::log10(x));
  const double fraction = x / std::pow(10.0, exponent);
  double nice;
  if (round) nice = fraction < 1.5 ? 1 : fraction < 3 ? 2 : fraction < 7 ? 5 : 10;
  else nice = fraction <= 1 ? 1 : fraction <= 2 ? 2 : fraction <= 5 ? 5 : 10;
  return nice * std::pow(10.0, exponent);
}

}  // namespace

std::string format_number(double value, int decimals) {
  const std::string digits = format("%.*f", std::max(decimals, 0), std::fabs(value));
  // Negative only if the printed magnitude is not zero ("-0.00" reads as 0).
  const bool negative = value < 0.0 && digits.find_first_not_of("0.") != std::string::npos;
  return negative ? "\u2212" + digits : digits;
}

std::vector<Tick> nice_ticks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  // A coarse step may leave a single tick inside a short range: refine until there are two.
  for (int wanted = std::max(target, 2); wanted <= std::max(target, 2) + 8 && ticks.size() < 2; ++wanted) {
    ticks.clear();
    const double step = nice_number(nice_number(hi - lo, false) / (wanted - 1), true);
    const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
    // A little slack so that a tick exactly at an end survives rounding of lo / step.
    const double slack = 1e-9 * step;
    const long first = static_cast<long>(std::ceil((lo - slack) / step));
    const long last = static_cast<long>(std::floor((hi + slack) / step));
    for (long k = first; k <= last; ++k) {
      const double v = static_cast<double>(k) * step;
      ticks.push_back({v, format_number(v, decimals)});
    }
  }
  return ticks;
}

}  // namespace bsmpm::render

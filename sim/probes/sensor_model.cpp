#include "probes/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bsmpm {

namespace {

// A series held sample by sample, as a piecewise-constant signal with its running integral.
class HeldSignal {
 public:
  // `first_interval` is how long the first sample holds when the series has one sample.
  HeldSignal(const Series& s, double first_interval) : y_(s.y) {
    if (s.t.size() != s.y.size()) throw std::invalid_argument("sensor model: t and y differ in length");
    for (std::size_t k = 1; k < s.t.size(); ++k)
      if (!(s.t[k] > s.t[k - 1])) throw std::invalid_argument("sensor model: sample times must increase");
    const std::size_t n = s.t.size();
    edges_.resize(n + 1);
    edges_[0] = s.t[0] - (n > 1 ? s.t[1] - s.t[0] : first_interval);
    std::copy(s.t.begin(), s.t.end(), edges_.begin() + 1);
    integral_.assign(n + 1, 0.0);
    for (std::size_t k = 0; k < n; ++k) integral_[k + 1] = integral_[k] + y_[k] * (edges_[k + 1] - edges_[k]);
  }

  double start() const { return edges_.front(); }
  double end() const { return edges_.back(); }

  // Mean of the signal over [a, b] clipped to its extent; NaN when nothing is left.
  double mean(double a, double b) const {
    a = std::max(a, start());
    b = std::min(b, end());
    if (!(b > a)) return std::nan("");
    return (integral_at(b) - integral_at(a)) / (b - a);
  }

 private:
  double integral_at(double x) const {
    // Segment k spans (edges_[k], edges_[k + 1]].
    const auto it = std::upper_bound(edges_.begin(), edges_.end(), x);
    const std::size_t k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - edges_.begin() - 1, 0));
    if (k >= y_.size()) return integral_.back();
    return integral_[k] + y_[k] * (x - edges_[k]);
  }

  std::vector<double> y_;
  std::vector<double> edges_;
  std::vector<double> integral_;
};

}  // namespace

Series resample(const Series& raw, double rate) {
  if (!(rate > 0.0)) throw std::invalid_argument("sensor model: the rate must be positive");
  Series out;
  if (raw.t.empty()) return out;
  const HeldSignal held(raw, 1.0 / rate);
  // Bins (j/f, (j+1)/f] from the one holding the signal's start to the one holding its end.
  const long first = static_cast<long>(std::floor(held.start() * rate));
  const long last = static_cast<long>(std::ceil(held.end() * rate)) - 1;
  for (long j = first; j <= last; ++j) {
    const double lo = j / rate, hi = (j + 1) / rate;
    const double value = held.mean(lo, hi);
    // A bin the signal only touches within round-off says nothing.
    if (std::isnan(value) || std::min(hi, held.end()) - std::max(lo, held.start()) < 1e-9 / rate) continue;
    out.t.push_back(hi);
    out.y.push_back(value);
  }
  return out;
}

Series moving_average(const Series& held_series, double window) {
  if (!(window >= 0.0)) throw std::invalid_argument("sensor model: the window must not be negative");
  if (window == 0.0 || held_series.t.size() < 2) return held_series;
  const HeldSignal held(held_series, 0.0);
  Series out;
  out.t = held_series.t;
  out.y.reserve(out.t.size());
  for (double tau : out.t) out.y.push_back(held.mean(tau - 0.5 * window, tau + 0.5 * window));
  return out;
}

Series apply_sensor_model(const Series& raw, const SensorModel& model) {
  return moving_average(resample(raw, model.rate), model.window);
}

}  // namespace bsmpm

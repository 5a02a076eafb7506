// The sensor model (sim/probes/sensor_model.hpp) on signals whose resampled and averaged
// values have closed forms: a constant, a ramp and a step.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "probes/sensor_model.hpp"

using namespace bsmpm;

namespace {

const double kRate = 20000.0;      // Hz
const double kBin = 1.0 / kRate;   // 50 us
const double kDelta = kBin / 4.0;  // four raw samples a bin

// Samples y(t_k) at t_k = k * kDelta, k = 1..n.
template <class F>
Series regular(int n, F&& y) {
  Series s;
  for (int k = 1; k <= n; ++k) {
    s.t.push_back(k * kDelta);
    s.y.push_back(y(k * kDelta));
  }
  return s;
}

}  // namespace

TEST_CASE("a constant stays constant at any sampling", "[sensor]") {
  Series s;
  double t = 0.0;
  for (int k = 0; k < 3000; ++k) {  // irregular steps of 7-43 us
    t += 7e-6 + 36e-6 * std::fmod(k * 0.618034, 1.0);
    s.t.push_back(t);
    s.y.push_back(2.5);
  }
  const Series r = resample(s, kRate);
  const Series f = apply_sensor_model(s, {kRate, 1e-3});
  REQUIRE(r.t.size() == f.t.size());
  REQUIRE(r.t.size() > 1400);  // 75 ms of signal
  for (std::size_t j = 0; j < f.t.size(); ++j) {
    CHECK(r.y[j] == Approx(2.5).epsilon(1e-12));
    CHECK(f.y[j] == Approx(2.5).epsilon(1e-12));
  }
  // Bins on the absolute grid, stamped at their ends.
  for (std::size_t j = 1; j < r.t.size(); ++j) CHECK(r.t[j] - r.t[j - 1] == Approx(kBin).epsilon(1e-9));
  CHECK(std::fmod(r.t[5] / kBin, 1.0) == Approx(0.0).margin(1e-6));
}

TEST_CASE("a ramp: bin means lag by half a bin less half a sample, the centred average restores it", "[sensor]") {
  const Series s = regular(4000, [](double t) { return 3.0 * t; });
  const Series r = resample(s, kRate);
  // Bin (jD, (j+1)D] holds samples 4j+1..4j+4, each over the kDelta before it: the mean
  // of those samples, 3 (tau - (D - delta) / 2) at the bin's end tau.
  REQUIRE(r.t.size() == 1000);
  for (std::size_t j = 0; j < r.t.size(); ++j)
    CHECK(r.y[j] == Approx(3.0 * (r.t[j] - 0.5 * (kBin - kDelta))).epsilon(1e-10));
  // A 1 ms window is 20 whole bins centred on tau: the mean of the bins j-9..j+10, that is
  // 3 (tau + D/2 - (D - delta)/2) = 3 (tau + delta/2), away from the ends.
  const Series f = moving_average(r, 1e-3);
  for (std::size_t j = 20; j + 20 < f.t.size(); ++j)
    CHECK(f.y[j] == Approx(3.0 * (f.t[j] + 0.5 * kDelta)).epsilon(1e-10));
}

TEST_CASE("a step: the bin holding it averages, the moving average ramps over the window", "[sensor]") {
  const int j0 = 500;  // the step rises after two of the four samples of bin j0
  const double rise = j0 * kBin + 2 * kDelta;
  const Series s = regular(4000, [&](double t) { return t > rise + 1e-12 ? 1.0 : 0.0; });
  const Series r = resample(s, kRate);
  REQUIRE(r.t.size() == 1000);
  CHECK(r.y[j0 - 1] == Approx(0.0).margin(1e-12));
  CHECK(r.y[j0] == Approx(0.5).epsilon(1e-12));
  CHECK(r.y[j0 + 1] == Approx(1.0).epsilon(1e-12));
  // Window at bin m spans bins m-9..m+10: (count of ones + 0.5 for bin j0) / 20.
  const Series f = moving_average(r, 1e-3);
  CHECK(f.y[j0 - 11] == Approx(0.0).margin(1e-12));
  CHECK(f.y[j0 - 10] == Approx(0.5 / 20).epsilon(1e-10));
  CHECK(f.y[j0] == Approx(10.5 / 20).epsilon(1e-10));
  CHECK(f.y[j0 + 5] == Approx(15.5 / 20).epsilon(1e-10));
  CHECK(f.y[j0 + 10] == Approx(1.0).epsilon(1e-12));
  // The peak of a short spike falls by the window's share of it.
  Series spike = regular(4000, [](double) { return 0.0; });
  for (int k = 4 * (j0 - 2); k < 4 * (j0 + 3); ++k) spike.y[k] = 1.0;  // bins j0-2 .. j0+2
  const Series g = apply_sensor_model(spike, {kRate, 1e-3});
  double peak = 0.0;
  for (double y : g.y) peak = std::max(peak, y);
  CHECK(peak == Approx(5.0 / 20).epsilon(1e-9));  // 5 bins of ones in a 20-bin window
}

TEST_CASE("a series already at the rate on its grid is left as it is by resampling", "[sensor]") {
  Series s;
  for (int k = 1; k <= 200; ++k) {
    s.t.push_back(k * kBin);
    s.y.push_back(std::sin(0.1 * k));
  }
  const Series r = resample(s, kRate);
  REQUIRE(r.t.size() == s.t.size());
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    CHECK(r.t[k] == Approx(s.t[k]).epsilon(1e-12));
    CHECK(r.y[k] == Approx(s.y[k]).margin(1e-9));
  }
  CHECK(moving_average(r, 0.0).y == r.y);  // no window: resampling only
}

TEST_CASE("the sensor model refuses times that do not increase", "[sensor]") {
  Series s{{0.1, 0.2, 0.2}, {1.0, 2.0, 3.0}};
  CHECK_THROWS_AS(resample(s, kRate), std::invalid_argument);
  CHECK_THROWS_AS(resample(Series{{0.1}, {1.0}}, 0.0), std::invalid_argument);
  CHECK(resample(Series{}, kRate).t.empty());
}

// The stripe number of a pressure cloud (sim/diagnostics/pressure_stripes.hpp) on lattices
// whose answer is known in closed form.
#include <catch2/catch.hpp>

#include <cmath>

#include "diagnostics/pressure_stripes.hpp"

using namespace bsmpm;

namespace {

// A unit lattice of n x n particles at integer coordinates, pressure f(column, row).
template <class F>
void lattice(int n, F f, std::vector<Vec2>& x, std::vector<double>& p) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      x.emplace_back(i, j);
      p.push_back(f(i, j));
    }
}

// Radius 2.2 on the unit lattice: 12 neighbours, 6 in the particle's column parity (offsets
// (0, +-1), (0, +-2), (+-2, 0)) and 6 in the other ((+-1, 0), (+-1, +-1)).
constexpr double kRadius = 2.2;
// A band that keeps every measured particle 2.2 or more inside the 20 x 20 lattice.
const StripeBand kInterior{3.0, 16.0, 3.0, 16.0};

}  // namespace

TEST_CASE("A linear pressure field has no stripes", "[unit][stripes]") {
  std::vector<Vec2> x;
  std::vector<double> p;
  lattice(20, [](int i, int j) { return 100.0 + 7.0 * i - 3.0 * j; }, x, p);
  const StripeSum s = pressure_stripes(x, p, std::vector<char>(x.size(), 1), kInterior, kRadius);
  CHECK(s.count == 14 * 14);
  CHECK(s.rms() < 1e-12);  // symmetric neighbourhoods: the mean is the centre's value
}

TEST_CASE("Columns alternating by +-a read a, over any linear field", "[unit][stripes]") {
  const double a = 250.0;
  std::vector<Vec2> x;
  std::vector<double> p;
  lattice(20, [&](int i, int j) { return 1000.0 + 5.0 * i + 2.0 * j + (i % 2 ? a : -a); }, x, p);
  // Each particle's 12 neighbours average to the linear part: the departure is +-a.
  const StripeSum s = pressure_stripes(x, p, std::vector<char>(x.size(), 1), kInterior, kRadius);
  CHECK(s.rms() == Approx(a).epsilon(1e-12));
}

TEST_CASE("The stripe number counts only the band's measured particles, against measured neighbours",
          "[unit][stripes]") {
  std::vector<Vec2> x;
  std::vector<double> p;
  lattice(20, [](int i, int) { return i % 2 ? 1.0 : -1.0; }, x, p);
  std::vector<char> measured(x.size(), 1);
  // Unmeasured particles (a solid's) carry a huge pressure: they must not enter the means.
  for (std::size_t k = 0; k < x.size(); ++k)
    if (x[k].y() >= 10.0) {
      measured[k] = 0;
      p[k] = 1.0e9;
    }
  // Rows 6 and 7 have all 12 neighbours (departure 1); row 8 loses (0, +2) to the solid:
  // 5 of its parity, 6 of the other, mean -1/11, departure 12/11.
  const StripeSum s = pressure_stripes(x, p, measured, StripeBand{3.0, 16.0, 6.0, 8.0}, kRadius);
  CHECK(s.count == 14 * 3);
  CHECK(s.rms() == Approx(std::sqrt((2.0 + 144.0 / 121.0) / 3.0)).epsilon(1e-12));
  // A band holding no particle reads nothing.
  CHECK(std::isnan(pressure_stripes(x, p, measured, StripeBand{3.0, 16.0, 30.0, 40.0}, kRadius).rms()));
}

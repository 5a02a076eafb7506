// The closed-form solution of scenes/elastic_column.toml (docs/method.md §11): a column of
// height H on a fixed floor, Poisson's ratio 0, stress-free at t = 0 when gravity g starts
// to act. Vertical displacement of the material point at height Y:
//   u(Y, t) = -(g / c^2)(H Y - Y^2 / 2) + sum_n b_n cos(c k_n t) sin(k_n Y),
//   k_n = (2n - 1) pi / (2H),  b_n = 2 g / (H c^2 k_n^3),
// the static compression plus the standing waves that make u(Y, 0) = 0.
#pragma once

#include <cmath>

namespace bsmpm::test {

struct ElasticColumn {
  double height = 1.0;        // H [m]
  double wave_speed = std::sqrt(1.0e8 / 1000.0);  // c = sqrt(E / rho) [m/s]
  double gravity = 9.81;      // g [m/s2]

  // The series summed in closed form (d'Alembert): the standing waves are the initial
  // displacement -u_s, extended oddly about the floor and evenly about the free top (period
  // 4H), carried half up and half down at speed c.
  double displacement(double Y, double t) const {
    const double ct = wave_speed * t;
    return static_sag(Y) - 0.5 * (extended_sag(Y - ct) + extended_sag(Y + ct));
  }
  // u_s(Y) = -(g / c^2)(H Y - Y^2 / 2)
  double static_sag(double Y) const {
    return -(gravity / (wave_speed * wave_speed)) * (height * Y - 0.5 * Y * Y);
  }
  // u_s extended: odd about Y = 0, even about Y = H, period 4H.
  double extended_sag(double Y) const {
    const double H = height;
    Y = std::fmod(Y, 4.0 * H);
    if (Y < -2.0 * H) Y += 4.0 * H;
    if (Y > 2.0 * H) Y -= 4.0 * H;
    if (Y < 0.0) return -extended_sag(-Y);
    return static_sag(Y > H ? 2.0 * H - Y : Y);
  }
  // The series itself, for the test that the closed form is the series (b_n ~ n^-3).
  double displacement_series(double Y, double t, int terms) const {
    const double H = height, c2 = wave_speed * wave_speed;
    double u = static_sag(Y);
    for (int n = 1; n <= terms; ++n) {
      const double k = (2 * n - 1) * M_PI / (2.0 * H);
      u += 2.0 * gravity / (H * c2 * k * k * k) * std::cos(wave_speed * k * t) * std::sin(k * Y);
    }
    return u;
  }
  double period() const { return 4.0 * height / wave_speed; }
  double largest_displacement() const { return gravity * height * height / (wave_speed * wave_speed); }
};

}  // namespace bsmpm::test

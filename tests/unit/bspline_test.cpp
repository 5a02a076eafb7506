// Properties of the clamped B-spline basis, for orders 1-3, at random points over the
// whole axis including the cells next to the walls (where the knots repeat).
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "bspline/clamped_bspline.hpp"

using namespace bsmpm;

namespace {
template <int P>
struct Order {
  static constexpr int value = P;
};
// Round-off scale: sums of at most 4 terms of order one.
constexpr double kTol = 1e-13;
}  // namespace

TEMPLATE_TEST_CASE("B-spline basis: partition of unity, zero gradient sum, non-negative", "[bspline]", Order<1>,
                   Order<2>, Order<3>) {
  constexpr int P = TestType::value;
  const double origin = -0.37, h = 0.013;
  const int cells = 23;
  ClampedBSpline<P> basis(origin, h, cells);
  REQUIRE(basis.basis_count() == cells + P);

  std::mt19937_64 rng(42 + P);
  std::uniform_real_distribution<double> anywhere(origin, origin + h * cells);
  std::uniform_real_distribution<double> near_wall(0.0, (P + 1) * h);
  std::vector<double> points;
  for (int k = 0; k < 2000; ++k) points.push_back(anywhere(rng));
  for (int k = 0; k < 500; ++k) points.push_back(origin + near_wall(rng));        // first cells
  for (int k = 0; k < 500; ++k) points.push_back(basis.end() - near_wall(rng));   // last cells
  points.push_back(origin);
  points.push_back(basis.end());

  for (double x : points) {
    typename ClampedBSpline<P>::Weights w, dw;
    const int first = basis.evaluate(x, w, dw);
    REQUIRE(first >= 0);
    REQUIRE(first + P < basis.basis_count());
    double sum = 0.0, dsum = 0.0;
    for (int a = 0; a <= P; ++a) {
      CHECK(w[a] >= -kTol);
      sum += w[a];
      dsum += dw[a];
    }
    CHECK(sum == Approx(1.0).margin(kTol));
    CHECK(dsum * h == Approx(0.0).margin(kTol));
  }
}

TEMPLATE_TEST_CASE("B-spline basis: closed-form kernel equals Cox-de Boor", "[bspline]", Order<1>, Order<2>, Order<3>) {
  constexpr int P = TestType::value;
  ClampedBSpline<P> basis(0.5, 0.02, 30);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> anywhere(basis.origin(), basis.end());
  for (int k = 0; k < 3000; ++k) {
    const double x = anywhere(rng);
    typename ClampedBSpline<P>::Weights w, dw, wr, dwr;
    REQUIRE(basis.evaluate(x, w, dw) == basis.evaluate_reference(x, wr, dwr));
    for (int a = 0; a <= P; ++a) {
      CHECK(w[a] == Approx(wr[a]).margin(1e-14));
      CHECK(dw[a] * 0.02 == Approx(dwr[a] * 0.02).margin(1e-13));
    }
  }
}

TEMPLATE_TEST_CASE("B-spline basis: linear precision with Greville abscissae", "[bspline]", Order<1>, Order<2>,
                   Order<3>) {
  // sum_i xi_i N_i(x) = x and sum_i xi_i N_i'(x) = 1: the control points at their Greville
  // abscissae reproduce a linear field exactly (de Boor), including next to the walls.
  constexpr int P = TestType::value;
  ClampedBSpline<P> basis(1.0, 0.1, 12);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> anywhere(basis.origin(), basis.end());
  for (int k = 0; k < 2000; ++k) {
    const double x = anywhere(rng);
    typename ClampedBSpline<P>::Weights w, dw;
    const int first = basis.evaluate(x, w, dw);
    double value = 0.0, slope = 0.0;
    for (int a = 0; a <= P; ++a) {
      value += basis.greville(first + a) * w[a];
      slope += basis.greville(first + a) * dw[a];
    }
    CHECK(value == Approx(x).margin(1e-13));
    CHECK(slope == Approx(1.0).margin(1e-12));
  }
}

TEST_CASE("Greville abscissae of the clamped knot vectors", "[bspline]") {
  const double o = 2.0, h = 0.5;
  const int n = 6;  // end = 5.0
  SECTION("order 1: the grid nodes") {
    ClampedBSpline<1> b(o, h, n);
    REQUIRE(b.basis_count() == 7);
    for (int i = 0; i < 7; ++i) CHECK(b.greville(i) == Approx(o + i * h));
  }
  SECTION("order 2: the walls and the cell centres") {
    ClampedBSpline<2> b(o, h, n);
    REQUIRE(b.basis_count() == 8);
    CHECK(b.greville(0) == Approx(2.0));
    for (int i = 1; i <= 6; ++i) CHECK(b.greville(i) == Approx(o + (i - 0.5) * h));
    CHECK(b.greville(7) == Approx(5.0));
  }
  SECTION("order 3: walls, h/3 from the walls, then the interior nodes") {
    ClampedBSpline<3> b(o, h, n);
    REQUIRE(b.basis_count() == 9);
    const double expected[9] = {2.0, 2.0 + h / 3, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0 - h / 3, 5.0};
    for (int i = 0; i < 9; ++i) CHECK(b.greville(i) == Approx(expected[i]));
  }
}

TEMPLATE_TEST_CASE("B-spline basis: interpolatory at the walls", "[bspline]", Order<1>, Order<2>, Order<3>) {
  constexpr int P = TestType::value;
  ClampedBSpline<P> b(0.0, 1.0, 8);
  typename ClampedBSpline<P>::Weights w, dw;
  REQUIRE(b.evaluate(0.0, w, dw) == 0);
  CHECK(w[0] == Approx(1.0));
  for (int a = 1; a <= P; ++a) CHECK(w[a] == Approx(0.0).margin(1e-15));
  const int last = b.evaluate(8.0, w, dw);
  CHECK(last + P == b.basis_count() - 1);
  CHECK(w[P] == Approx(1.0));
  for (int a = 0; a < P; ++a) CHECK(w[a] == Approx(0.0).margin(1e-15));
}

TEMPLATE_TEST_CASE("B-spline basis: integrals add up to the domain length", "[bspline]", Order<1>, Order<2>, Order<3>) {
  constexpr int P = TestType::value;
  ClampedBSpline<P> b(0.0, 0.25, 10);
  double total = 0.0;
  for (int i = 0; i < b.basis_count(); ++i) total += b.integral(i);
  CHECK(total == Approx(2.5));
  // Midpoint quadrature of N_0 over the first cells matches its stated integral.
  double q = 0.0;
  const int samples = 200000;
  for (int k = 0; k < samples * (P + 1) / 10; ++k) {
    const double x = (k + 0.5) * 2.5 / samples;
    typename ClampedBSpline<P>::Weights w, dw;
    if (b.evaluate(x, w, dw) == 0) q += w[0] * 2.5 / samples;
  }
  CHECK(q == Approx(b.integral(0)).epsilon(1e-6));
}

TEMPLATE_TEST_CASE("B-spline basis: integrals over a part of the axis", "[bspline]", Order<1>, Order<2>, Order<3>) {
  // add_integrals (the wall_reaction sensor's shares, docs/method.md §8): over the whole
  // axis each function's integral; over [a, b] they add up to b - a (partition of unity);
  // two adjacent parts add up to their union; a part beyond the axis is clipped to it.
  constexpr int P = TestType::value;
  ClampedBSpline<P> b(0.1, 0.25, 10);
  const int n = b.basis_count();
  std::vector<double> whole(n, 0.0);
  b.add_integrals(0.1, 2.6, whole);
  for (int i = 0; i < n; ++i) CHECK(whole[i] == Approx(b.integral(i)).margin(kTol));
  std::vector<double> left(n, 0.0), right(n, 0.0), both(n, 0.0);
  b.add_integrals(0.03, 0.777, left);   // starts before the axis, ends inside a cell
  b.add_integrals(0.777, 1.9, right);
  b.add_integrals(0.1, 1.9, both);
  double sum_left = 0.0;
  for (int i = 0; i < n; ++i) {
    sum_left += left[i];
    CHECK(left[i] + right[i] == Approx(both[i]).margin(kTol));
    CHECK(left[i] >= 0.0);
  }
  CHECK(sum_left == Approx(0.777 - 0.1).margin(kTol));
}

// Reference B-spline evaluation on an arbitrary non-decreasing knot vector
// (Piegl & Tiller, The NURBS Book, 2nd ed., algorithms A2.2/A2.3).
// Used for the cells next to the walls, where the clamped knots are repeated, and by the
// tests as the reference that the closed-form uniform kernel is checked against.
#pragma once

#include <array>

namespace bsmpm {

// Values N_{span-p..span} and first derivatives at u, where knots[span] <= u < knots[span+1]
// (or u == knots[span+1] at the last span). `knot(j)` returns the j-th knot.
template <int P, class KnotFn>
void cox_de_boor(int span, double u, KnotFn&& knot, std::array<double, P + 1>& value,
                 std::array<double, P + 1>& derivative) {
  // ndu: upper triangle holds basis values, lower triangle the knot differences.
  double ndu[P + 1][P + 1];
  double left[P + 1], right[P + 1];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= P; ++j) {
    left[j] = u - knot(span + 1 - j);
    right[j] = knot(span + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int r = 0; r <= P; ++r) {
    value[r] = ndu[r][P];
    double d = 0.0;
    if constexpr (P > 0) {
      if (r >= 1) d += ndu[r - 1][P - 1] / ndu[P][r - 1];
      if (r <= P - 1) d -= ndu[r][P - 1] / ndu[P][r];
    }
    derivative[r] = P * d;
  }
}

}  // namespace bsmpm

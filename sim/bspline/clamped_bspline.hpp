// B-spline basis of degree P over an open (clamped) uniform knot vector on [origin,
// origin + n_cells h]: the end knots are repeated P+1 times, so there are n_cells + P
// basis functions, the end ones interpolate at the walls and the basis is a partition of
// unity everywhere (docs/method.md §1; Gan et al. 2018, IJNME 113:411).
//
// The degrees of freedom are the control points; their positions are the Greville
// abscissae xi_i = (t_{i+1} + ... + t_{i+P}) / P.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "bspline/cox_de_boor.hpp"

namespace bsmpm {

template <int P>
class ClampedBSpline {
  static_assert(P >= 1 && P <= 3, "B-spline order must be 1, 2 or 3");

 public:
  static constexpr int kOrder = P;
  static constexpr int kSupport = P + 1;  // non-zero functions per point and axis
  using Weights = std::array<double, P + 1>;

  ClampedBSpline() = default;
  ClampedBSpline(double origin, double cell_size, int cells)
      : origin_(origin), h_(cell_size), inv_h_(1.0 / cell_size), cells_(cells) {}

  double origin() const { return origin_; }
  double cell_size() const { return h_; }
  int cells() const { return cells_; }
  int basis_count() const { return cells_ + P; }
  double end() const { return origin_ + h_ * cells_; }

  // j-th knot, j in [0, cells + 2P].
  double knot(int j) const { return origin_ + h_ * std::clamp(j - P, 0, cells_); }

  double greville(int i) const {
    double s = 0.0;
    for (int k = 1; k <= P; ++k) s += knot(i + k);
    return s / P;
  }

  // Integral of N_i over the axis: (t_{i+P+1} - t_i) / (P+1).
  double integral(int i) const { return (knot(i + P + 1) - knot(i)) / (P + 1); }

  // Adds the integral of every N_i over [a, b] (clipped to the axis) to out[i]; out has
  // basis_count() entries. Three Gauss points per cell piece: exact for degree P <= 3.
  void add_integrals(double a, double b, std::vector<double>& out) const {
    a = std::max(a, origin_);
    b = std::min(b, end());
    static constexpr double kNode = 0.7745966692414834, kEdge = 5.0 / 9.0, kMiddle = 8.0 / 9.0;
    for (int c = cell_of(a); c < cells_; ++c) {
      const double lo = std::max(a, origin_ + h_ * c), hi = std::min(b, origin_ + h_ * (c + 1));
      if (!(hi > lo)) break;
      const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
      for (const auto& [u, weight] : {std::pair{-kNode, kEdge}, std::pair{0.0, kMiddle}, std::pair{kNode, kEdge}}) {
        Weights w, dw;
        const int first = evaluate(mid + u * half, w, dw);  // inside cell c: first == c
        for (int k = 0; k <= P; ++k) out[first + k] += weight * half * w[k];
      }
    }
  }

  // Range [first, last] of the basis functions that are non-zero somewhere on [a, b]
  // (a <= b; a point when a == b). last < first when there is none.
  std::pair<int, int> support_range(double a, double b) const {
    if (a == b) {
      Weights w, dw;
      const int first = evaluate(a, w, dw);
      int lo = first + P + 1, hi = first - 1;
      for (int k = 0; k <= P; ++k)
        if (w[k] > 0.0) {
          lo = std::min(lo, first + k);
          hi = std::max(hi, first + k);
        }
      return {lo, hi};
    }
    int lo = basis_count(), hi = -1;
    for (int i = 0; i < basis_count(); ++i)
      if (knot(i) < b && knot(i + P + 1) > a) {  // open support (t_i, t_{i+P+1}) meets (a, b)
        lo = std::min(lo, i);
        hi = std::max(hi, i);
      }
    return {lo, hi};
  }

  // Cell containing x (points outside are attributed to the nearest cell).
  int cell_of(double x) const {
    const int c = static_cast<int>(std::floor((x - origin_) * inv_h_));
    return std::clamp(c, 0, cells_ - 1);
  }

  // Fills the P+1 non-zero values and derivatives at x; returns the index of the first
  // non-zero function (which equals the cell index).
  int evaluate(double x, Weights& w, Weights& dw) const {
    const int c = cell_of(x);
    if (c >= P - 1 && c <= cells_ - P) {
      uniform((x - origin_) * inv_h_ - c, w, dw);
    } else {
      cox_de_boor<P>(c + P, x, [this](int j) { return knot(j); }, w, dw);
    }
    return c;
  }

  // Same as evaluate() but always through the general recursion (reference kernel).
  int evaluate_reference(double x, Weights& w, Weights& dw) const {
    const int c = cell_of(x);
    cox_de_boor<P>(c + P, x, [this](int j) { return knot(j); }, w, dw);
    return c;
  }

 private:
  // Closed-form uniform cardinal B-spline pieces, u in [0, 1] within the cell.
  void uniform(double u, Weights& w, Weights& dw) const {
    const double v = 1.0 - u;
    if constexpr (P == 1) {
      w = {v, u};
      dw = {-inv_h_, inv_h_};
    } else if constexpr (P == 2) {
      w = {0.5 * v * v, 0.5 + u * v, 0.5 * u * u};
      dw = {-v * inv_h_, (1.0 - 2.0 * u) * inv_h_, u * inv_h_};
    } else {
      const double u2 = u * u, u3 = u2 * u;
      w = {v * v * v / 6.0, (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0,
           (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0, u3 / 6.0};
      dw = {-0.5 * v * v * inv_h_, (1.5 * u2 - 2.0 * u) * inv_h_,
            (-1.5 * u2 + u + 0.5) * inv_h_, 0.5 * u2 * inv_h_};
    }
  }

  double origin_ = 0.0;
  double h_ = 1.0;
  double inv_h_ = 1.0;
  int cells_ = 1;
};

}  // namespace bsmpm

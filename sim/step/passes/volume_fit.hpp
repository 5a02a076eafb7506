// The least-squares linear fit of the fluid's volume ratio at one control point
// (docs/method.md §4), shared by the fits on the velocity's splines and on the hats.
#pragma once

namespace bsmpm {

// mom holds sum w, sum w d (2), sum w d d^T (3: xx, xy, yy), sum w J, sum w J d (2) of the
// particles around the control point (w = m S, d the offset in cells). The normal equations
// A (J_I, g_I h) = r are solved by cofactors and the fit replaces the first three moments.
// Where the particles do not span a plane (a thin film cannot carry a gradient across
// itself: their spread about the centroid, in cells^2, below 1e-3), the mass average.
inline void fit_volume_moments(double* mom) {
  const double a00 = mom[0];
  if (a00 <= 0.0) return;
  const double a01 = mom[1], a02 = mom[2], a11 = mom[3], a12 = mom[4], a22 = mom[5];
  const double r0 = mom[6], r1 = mom[7], r2 = mom[8];
  const double mx = a01 / a00, my = a02 / a00;
  const double cxx = a11 / a00 - mx * mx, cxy = a12 / a00 - mx * my, cyy = a22 / a00 - my * my;
  double fit0 = r0 / a00, fit1 = 0.0, fit2 = 0.0;
  if (cxx * cyy - cxy * cxy > 1e-3) {
    const double c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22, c02 = a01 * a12 - a02 * a11;
    const double c11 = a00 * a22 - a02 * a02, c12 = a01 * a02 - a00 * a12, c22 = a00 * a11 - a01 * a01;
    const double inv_det = 1.0 / (a00 * c00 + a01 * c01 + a02 * c02);
    fit0 = (c00 * r0 + c01 * r1 + c02 * r2) * inv_det;
    fit1 = (c01 * r0 + c11 * r1 + c12 * r2) * inv_det;
    fit2 = (c02 * r0 + c12 * r1 + c22 * r2) * inv_det;
  }
  mom[0] = fit0;
  mom[1] = fit1;
  mom[2] = fit2;
}

}  // namespace bsmpm

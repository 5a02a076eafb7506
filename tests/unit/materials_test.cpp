// Constitutive models: equations of state and elastic stress.
#include <catch2/catch.hpp>

#include <cmath>

#include "materials/elastic_solid.hpp"
#include "materials/weakly_compressible_fluid.hpp"

using namespace bsmpm;

TEST_CASE("Fluid equations of state invert and give the sound speed", "[materials]") {
  for (auto eos : {EquationOfState::kLinear, EquationOfState::kTait}) {
    WeaklyCompressibleFluid f;
    f.bulk_modulus = 1e6;
    f.density = 1000.0;
    f.eos = eos;
    for (double p : {-2e3, 0.0, 3e3, 5e4}) {
      const double J = f.volume_ratio(p);
      CHECK(f.pressure(J) == Approx(p).margin(1e-9));
      // c^2 = dp/drho by central differences, rho = rho0 / J.
      const double rho = f.density / J, d = 1e-6 * rho;
      const double dp = f.pressure(f.density / (rho + d)) - f.pressure(f.density / (rho - d));
      CHECK(std::sqrt(dp / (2 * d)) == Approx(f.sound_speed(J)).epsilon(1e-6));
    }
    CHECK(f.sound_speed(1.0) == Approx(std::sqrt(1e6 / 1000.0)));
  }
}

TEST_CASE("Viscous stress is the plane-strain deviator of the rate of deformation", "[materials]") {
  WeaklyCompressibleFluid f;
  f.viscosity = 2.0;
  Mat2 L;
  L << 1.0, 3.0, -1.0, 2.0;
  const Mat2 s = f.stress<true>(10.0, L);
  // D = [[1, 1], [1, 2]], tr D = 3, dev D = D - I.
  CHECK(s(0, 0) == Approx(-10.0 + 2 * 2.0 * (1.0 - 1.0)));
  CHECK(s(1, 1) == Approx(-10.0 + 2 * 2.0 * (2.0 - 1.0)));
  CHECK(s(0, 1) == Approx(2 * 2.0 * 1.0));
  CHECK(s(0, 1) == s(1, 0));
  const Mat2 inviscid = f.stress<false>(10.0, L);
  CHECK(inviscid == -10.0 * Mat2::Identity());
}

TEST_CASE("Elastic models: stress-free at rest, objective, linear for small strain", "[materials]") {
  for (auto model : {ElasticModel::kNeoHookean, ElasticModel::kSaintVenantKirchhoff}) {
    ElasticSolid e;
    e.youngs_modulus = 1e6;
    e.poisson_ratio = 0.3;
    e.model = model;
    CHECK(e.stress(Mat2::Identity()).norm() == Approx(0.0).margin(1e-9));

    Mat2 F;
    F << 1.05, 0.02, -0.03, 0.97;
    const double a = 0.7;
    Mat2 R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    const Mat2 rotated = e.stress(R * F), expected = R * e.stress(F) * R.transpose();
    CHECK((rotated - expected).norm() <= 1e-9 * expected.norm());

    // Small plane-strain stretch eps in x: sigma_xx = (lambda + 2 mu) eps, sigma_yy = lambda eps.
    const double eps = 1e-6;
    Mat2 Fs = Mat2::Identity();
    Fs(0, 0) += eps;
    const Mat2 s = e.stress(Fs);
    CHECK(s(0, 0) == Approx((e.lame_lambda() + 2 * e.shear_modulus()) * eps).epsilon(1e-4));
    CHECK(s(1, 1) == Approx(e.lame_lambda() * eps).epsilon(1e-4));
    // A rigid rotation alone carries no stress.
    CHECK(e.stress(R).norm() <= 1e-9);
  }
}

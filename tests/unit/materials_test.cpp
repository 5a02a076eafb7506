// Constitutive models: equations of state and elastic stress.
#include <catch2/catch.hpp>

#include <cmath>

#include "materials/elastic_solid.hpp"
#include "materials/weakly_compressible_fluid.hpp"

using namespace bsmpm;

namespace {
// Water of K = 1 MPa, rho0 = 1000 kg/m3 with the given equation of state.
WeaklyCompressibleFluid water(EquationOfState eos) {
  WeaklyCompressibleFluid f;
  f.bulk_modulus = 1e6;
  f.density = 1000.0;
  f.eos = eos;
  return f;
}
}  // namespace

TEST_CASE("Fluid equations of state invert and give the sound speed", "[materials]") {
  for (auto eos : {EquationOfState::kLinear, EquationOfState::kTait}) {
    WeaklyCompressibleFluid f = water(eos);
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

TEST_CASE("Equations of state give the closed-form pressure at a given density", "[materials]") {
  // K = 1 MPa, rho0 = 1000 kg/m3; rho / rho0 = 1 / J. The values are the closed forms
  // evaluated by hand (docs/method.md §4), so a wrong exponent or factor cannot pass.
  WeaklyCompressibleFluid f;
  f.bulk_modulus = 1e6;
  f.density = 1000.0;
  f.eos = EquationOfState::kLinear;  // p = K (rho/rho0 - 1)
  CHECK(f.pressure(1.0 / 1.01) == Approx(1.0e4).epsilon(1e-12));
  CHECK(f.pressure(1.0 / 0.99) == Approx(-1.0e4).epsilon(1e-12));
  f.eos = EquationOfState::kTait;  // p = K/7 ((rho/rho0)^7 - 1); exponent 1 would give 1e4
  CHECK(f.pressure(1.0 / 1.01) == Approx(10305.0503010014).epsilon(1e-12));  // K/7 (1.01^7 - 1)
  CHECK(f.pressure(1.0 / 0.99) == Approx(-9704.9502990014).epsilon(1e-12));  // K/7 (0.99^7 - 1)
  f.tait_gamma = 3.0;  // the std::pow branch: p = K/3 ((rho/rho0)^3 - 1)
  CHECK(f.pressure(1.0 / 1.01) == Approx(10100.3333333334).epsilon(1e-12));
  // Sound speed c^2 = (K / rho0) (rho/rho0)^(gamma - 1).
  CHECK(f.sound_speed(1.0 / 1.01) == Approx(std::sqrt(1000.0 * 1.01 * 1.01)).epsilon(1e-12));
}

TEST_CASE("The tension cut-off bounds the pressure from below and leaves compression alone", "[materials]") {
  // materials.<name>.min_pressure (docs/method.md §4): p = max(p_EOS, p_min).
  for (auto eos : {EquationOfState::kLinear, EquationOfState::kTait}) {
    WeaklyCompressibleFluid f = water(eos);
    const double stretched = f.pressure(1.01), compressed = f.pressure(0.99);
    REQUIRE(stretched < -9e3);  // J = 1.01 carries about -10 kPa without the cut-off
    f.min_pressure = 0.0;
    CHECK(f.pressure(1.01) == 0.0);
    CHECK(f.pressure(0.99) == compressed);
    f.min_pressure = -2e3;
    CHECK(f.pressure(1.01) == -2e3);
    CHECK(f.pressure(1.0005) == Approx(eos == EquationOfState::kLinear ? 1e6 * (1 / 1.0005 - 1)
                                                                      : 1e6 / 7 * (std::pow(1 / 1.0005, 7) - 1)));
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

TEST_CASE("Elastic models at finite strain equal their closed forms", "[materials]") {
  // E = 1 MPa, nu = 0.3: lambda = E nu / ((1 + nu)(1 - 2 nu)) = 576923.08 Pa,
  // mu = E / (2 (1 + nu)) = 384615.38 Pa (plane strain). A 20 % stretch in x, F = diag(1.2, 1),
  // J = 1.2, with the values evaluated by hand from the formulas in docs/method.md §5.
  ElasticSolid e;
  e.youngs_modulus = 1e6;
  e.poisson_ratio = 0.3;
  REQUIRE(e.lame_lambda() == Approx(576923.076923077).epsilon(1e-12));
  REQUIRE(e.shear_modulus() == Approx(384615.384615385).epsilon(1e-12));
  Mat2 F = Mat2::Identity();
  F(0, 0) = 1.2;
  SECTION("Neo-Hookean: sigma = mu/J (F F^T - I) + lambda ln(J)/J I") {
    e.model = ElasticModel::kNeoHookean;
    const Mat2 s = e.stress(F);
    CHECK(s(0, 0) == Approx(228680.235638119).epsilon(1e-12));  // mu 0.44 / 1.2 + lambda ln 1.2 / 1.2
    CHECK(s(1, 1) == Approx(87654.5946124782).epsilon(1e-12));   // lambda ln 1.2 / 1.2
    CHECK(s(0, 1) == 0.0);
    CHECK(s(1, 0) == 0.0);
    // Simple shear F = [[1, g], [0, 1]], J = 1: sigma = mu [[g^2, g], [g, 0]] (F^T F would
    // put g^2 on the other diagonal entry).
    Mat2 shear = Mat2::Identity();
    shear(0, 1) = 0.3;
    const Mat2 t = e.stress(shear);
    CHECK(t(0, 0) == Approx(e.shear_modulus() * 0.09).epsilon(1e-12));
    CHECK(t(0, 1) == Approx(e.shear_modulus() * 0.3).epsilon(1e-12));
    CHECK(t(1, 0) == Approx(e.shear_modulus() * 0.3).epsilon(1e-12));
    CHECK(std::abs(t(1, 1)) <= 1e-9 * e.shear_modulus());
  }
  SECTION("Saint Venant-Kirchhoff: sigma = F (lambda tr(E) I + 2 mu E) F^T / J") {
    e.model = ElasticModel::kSaintVenantKirchhoff;
    const Mat2 s = e.stress(F);  // E = diag(0.22, 0)
    CHECK(s(0, 0) == Approx(355384.615384615).epsilon(1e-12));  // 1.44 (lambda + 2 mu) 0.22 / 1.2
    CHECK(s(1, 1) == Approx(105769.230769231).epsilon(1e-12));  // lambda 0.22 / 1.2
    CHECK(s(0, 1) == 0.0);
    CHECK(s(1, 0) == 0.0);
  }
}

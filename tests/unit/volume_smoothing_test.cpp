// The fluid's J fitted through the grid (docs/method.md §4), on the velocity's splines and on
// the linear ones: a linear J comes back exactly at every particle, walls included, and
// particle-to-particle noise comes back smaller.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "step/bsmpm_simulation.hpp"
#include "step/passes/linear_volume_smoothing.hpp"
#include "step/passes/volume_smoothing.hpp"
#include "unit/one_body_state.hpp"

using namespace bsmpm;

namespace {

template <int P>
struct Order {
  static constexpr int value = P;
};

// 3,000 particles at random on a 12 x 9 grid of [0, 1.2] x [0, 0.9] (about 28 a cell, so
// every control point's particles span a plane), random masses, J = J(x).
template <int P, class Field>
std::unique_ptr<BsmpmSimulation<P>> cloud_with(Field&& J) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> ux(0.0, 1.2), uy(0.0, 0.9), um(0.5, 2.0);
  WeaklyCompressibleFluid fluid;
  fluid.bulk_modulus = 1e4;
  StepState<P> st = test::one_body_state(Grid<P>(Vec2(0.0, 0.0), Vec2(0.1, 0.1), 12, 9), "cloud", fluid,
                                         Vec2(0.02, 0.02), [&](Particles& ps) {
                                           for (int k = 0; k < 3000; ++k) {
                                             const Vec2 x(ux(rng), uy(rng));
                                             ps.push_back(x, um(rng), 1e-3, 0);
                                             ps.J.back() = J(x);
                                           }
                                         });
  SolverSettings settings;
  auto sim = test::bare_simulation(std::move(st), settings);
  sim->compute_weights();
  return sim;
}

// Every particle's fitted J, by the fit on the velocity's splines (linear = 0), the hats (1)
// or the knots' patches of four cells (2).
template <int P>
std::vector<double> fitted(const StepState<P>& st, int linear, bool values_only) {
  std::vector<double> J(st.particles.size());
  const long n = static_cast<long>(st.particles.size());
  if (linear) {
    LinearVolumeSmoothing<P> s(st.grid, values_only, linear == 2);
    s.begin(NodeBox{0, st.grid.nx(), 0, st.grid.ny()});
    for (long p = 0; p < n; ++p) s.add_moments(st, static_cast<std::uint32_t>(p));
    s.fit();
    for (long p = 0; p < n; ++p) J[p] = s.fitted_volume_ratio(st, p);
  } else {
    VolumeSmoothing<P> s(st.grid, values_only);
    for (long p = 0; p < n; ++p) s.add_moments(st, static_cast<std::uint32_t>(p));
    s.fit(NodeBox{0, st.grid.nx(), 0, st.grid.ny()}, st.grid.ny());
    for (long p = 0; p < n; ++p) J[p] = s.fitted_volume_ratio(st, p);
  }
  return J;
}

}  // namespace

// On the velocity's splines of order 2 and 3, the corner control point's function lives in the
// corner cell only, peaked at the corner: its particles' spread, about 0.04 cells^2 per axis,
// is at the thin-film threshold (1e-3 for the product), and where it falls below (here at all
// four corners) the fit takes the mass average there, which is not exact. The hats' corner
// spread is 0.056 per axis.
template <int P>
bool in_corner_cell(const StepState<P>& st, std::size_t p) {
  const Vec2& x = st.particles.x[p];
  return (x.x() < 0.1 || x.x() > 1.1) && (x.y() < 0.1 || x.y() > 0.8);
}

TEMPLATE_TEST_CASE("The J fit reproduces a linear J at every particle, on either basis and readback", "[smoothing]",
                   Order<1>, Order<2>, Order<3>) {
  constexpr int P = TestType::value;
  auto linear_J = [](const Vec2& x) { return 1.0 + 0.01 * x.x() - 0.02 * x.y(); };
  auto sim = cloud_with<P>(linear_J);
  const auto& st = sim->state();
  for (int linear : {0, 1, 2})
    for (bool values_only : {false, true}) {
      const std::vector<double> J = fitted(st, linear, values_only);
      double worst = 0.0;
      for (std::size_t p = 0; p < J.size(); ++p)
        if (linear || !in_corner_cell(st, p)) worst = std::max(worst, std::abs(J[p] - linear_J(st.particles.x[p])));
      INFO("linear basis " << linear << ", values only " << values_only);
      CHECK(worst <= 1e-12);
    }
}

TEMPLATE_TEST_CASE("The J fit shrinks particle-to-particle noise about a linear J", "[smoothing]", Order<2>, Order<3>) {
  // Noise of +-1e-3 on each particle: a fit over about 28 x 9 particles passes a fraction of
  // it back (measured below 0.4 of the noise's RMS on both bases); a readback that returned
  // each particle its own J would keep all of it.
  constexpr int P = TestType::value;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  std::vector<double> e;
  auto sim = cloud_with<P>([&](const Vec2& x) {
    e.push_back(noise(rng));
    return 1.0 + 0.01 * x.x() + e.back();
  });
  const auto& st = sim->state();
  double rms_in = 0.0;
  for (double v : e) rms_in += v * v;
  rms_in = std::sqrt(rms_in / e.size());
  for (int linear : {0, 1, 2}) {
    const std::vector<double> J = fitted(st, linear, false);
    double rms = 0.0;
    for (std::size_t p = 0; p < J.size(); ++p) {
      const double d = J[p] - (1.0 + 0.01 * st.particles.x[p].x());
      rms += d * d;
    }
    rms = std::sqrt(rms / J.size());
    INFO("linear basis " << linear << ": RMS " << rms / rms_in << " of the noise's");
    CHECK(rms < 0.4 * rms_in);
  }
}

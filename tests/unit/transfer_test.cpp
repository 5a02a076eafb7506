// Particle-to-grid and grid-to-particle transfers conserve mass and momentum to round-off.
#include <catch2/catch.hpp>

#include <random>

#include "step/bsmpm_simulation.hpp"

using namespace bsmpm;

namespace {

template <int P>
struct Order {
  static constexpr int value = P;
};

// A 12 x 9 grid on [0, 1.2] x [0, 0.9] with randomly placed particles (some in the cells next
// to the walls), random masses, velocities and stresses, and no effects at all.
template <int P>
std::unique_ptr<BsmpmSimulation<P>> random_cloud(unsigned seed) {
  StepState<P> st;
  st.grid = Grid<P>(Vec2(0.0, 0.0), Vec2(0.1, 0.1), 12, 9);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, 1.2), uy(0.0, 0.9), um(0.5, 2.0), uv(-1.0, 1.0);
  Body body;
  body.name = "cloud";
  WeaklyCompressibleFluid fluid;
  fluid.bulk_modulus = 1e4;
  body.material = fluid;
  body.begin = 0;
  for (int k = 0; k < 400; ++k) {
    st.particles.push_back(Vec2(ux(rng), uy(rng)), um(rng), 1e-3, 0);
    st.particles.v.back() = Vec2(uv(rng), uv(rng));
    Mat2 s;
    s << uv(rng), uv(rng), 0.0, uv(rng);
    s(1, 0) = s(0, 1);
    st.particles.stress.back() = 1e3 * s;
  }
  body.end = st.particles.size();
  body.spacing = Vec2(0.05, 0.05);
  st.bodies.push_back(body);
  st.layers.resize(1);
  SolverSettings settings;
  settings.mass_cutoff_ratio = 0.0;  // keep every node: conservation is then exact
  return std::make_unique<BsmpmSimulation<P>>(std::move(st), settings, std::vector<std::unique_ptr<Effect<P>>>{},
                                              std::vector<std::unique_ptr<Probe>>{});
}

}  // namespace

TEMPLATE_TEST_CASE("P2G conserves mass and momentum; internal forces sum to zero", "[transfer]", Order<1>, Order<2>,
                   Order<3>) {
  constexpr int P = TestType::value;
  auto sim = random_cloud<P>(3);
  auto& st = sim->state();
  double mass = 0.0;
  Vec2 momentum = Vec2::Zero();
  for (std::size_t p = 0; p < st.particles.size(); ++p) {
    mass += st.particles.mass[p];
    momentum += st.particles.mass[p] * st.particles.v[p];
  }
  sim->compute_weights();
  sim->particle_to_grid();
  const GridLayer& g = st.layers[0];
  double grid_mass = 0.0;
  Vec2 grid_momentum = Vec2::Zero(), grid_force = Vec2::Zero();
  double force_scale = 0.0;
  for (int n = 0; n < st.grid.node_count(); ++n) {
    grid_mass += g.mass[n];
    grid_momentum += g.momentum[n];
    grid_force += g.force[n];
    force_scale += g.force[n].norm();
  }
  CHECK(grid_mass == Approx(mass).epsilon(1e-14));
  CHECK((grid_momentum - momentum).norm() <= 1e-13 * mass);
  REQUIRE(force_scale > 0.0);
  CHECK(grid_force.norm() <= 1e-13 * force_scale);  // sum_I grad S_I = 0
}

TEMPLATE_TEST_CASE("A full step without external forces conserves total momentum", "[transfer]", Order<1>, Order<2>,
                   Order<3>) {
  constexpr int P = TestType::value;
  auto sim = random_cloud<P>(5);
  const Particles& ps = sim->particles();
  auto total = [&] {
    Vec2 m = Vec2::Zero();
    for (std::size_t p = 0; p < ps.size(); ++p) m += ps.mass[p] * ps.v[p];
    return m;
  };
  const Vec2 before = total();
  double scale = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) scale += ps.mass[p] * ps.v[p].norm();
  for (int k = 0; k < 20; ++k) sim->advance(1e-4);
  const Vec2 after = total();
  // 20 steps of sums over ~400 particles: round-off far below 1e-12 of the momentum scale.
  CHECK((after - before).norm() <= 1e-12 * scale);
}

TEMPLATE_TEST_CASE("G2P reproduces a uniform and a linear velocity field", "[transfer]", Order<1>, Order<2>, Order<3>) {
  constexpr int P = TestType::value;
  auto sim = random_cloud<P>(9);
  auto& st = sim->state();
  sim->compute_weights();
  const int ny = st.grid.ny();
  // Linear field v(x) = A x + b on the control points at their Greville abscissae.
  Mat2 A;
  A << 0.3, -1.2, 0.7, 0.1;
  const Vec2 b(0.5, -0.25);
  std::vector<Vec2> v(st.grid.node_count());
  for (int i = 0; i < st.grid.nx(); ++i)
    for (int j = 0; j < ny; ++j) v[i * ny + j] = A * st.grid.greville(i, j) + b;
  for (std::size_t p = 0; p < st.particles.size(); ++p) {
    const auto& w = st.weights[p];
    Vec2 vp = Vec2::Zero();
    Mat2 L = Mat2::Zero();
    for (int a = 0; a <= P; ++a)
      for (int c = 0; c <= P; ++c) {
        const Vec2& vi = v[(w.i0 + a) * ny + w.j0 + c];
        vp += w.wx[a] * w.wy[c] * vi;
        L += vi * Vec2(w.gx[a] * w.wy[c], w.wx[a] * w.gy[c]).transpose();
      }
    CHECK((vp - (A * st.particles.x[p] + b)).norm() <= 1e-12);
    CHECK((L - A).norm() <= 1e-11);  // the velocity gradient of eq. 14 is exact
  }
}

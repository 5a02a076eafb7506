// Particle-to-grid and grid-to-particle transfers: conservation to round-off, and the exact
// reproduction of linear velocity fields by the solver's own gather and velocity gradient.
#include <catch2/catch.hpp>

#include <random>

#include "step/bsmpm_simulation.hpp"
#include "step/passes/grid_to_particle.hpp"
#include "unit/one_body_state.hpp"

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
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, 1.2), uy(0.0, 0.9), um(0.5, 2.0), uv(-1.0, 1.0);
  WeaklyCompressibleFluid fluid;
  fluid.bulk_modulus = 1e4;
  StepState<P> st = test::one_body_state(Grid<P>(Vec2(0.0, 0.0), Vec2(0.1, 0.1), 12, 9), "cloud", fluid,
                                         Vec2(0.05, 0.05), [&](Particles& ps) {
                                           for (int k = 0; k < 400; ++k) {
                                             ps.push_back(Vec2(ux(rng), uy(rng)), um(rng), 1e-3, 0);
                                             ps.v.back() = Vec2(uv(rng), uv(rng));
                                             Mat2 s;
                                             s << uv(rng), uv(rng), 0.0, uv(rng);
                                             s(1, 0) = s(0, 1);
                                             ps.stress.back() = 1e3 * s;
                                           }
                                         });
  SolverSettings settings;
  settings.mass_cutoff_ratio = 0.0;  // keep every node: conservation is then exact
  return test::bare_simulation(std::move(st), settings);
}

}  // namespace

TEMPLATE_TEST_CASE("P2G conserves mass and momentum and its internal forces sum to zero", "[transfer]", Order<1>, Order<2>,
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

TEMPLATE_TEST_CASE("G2P reproduces a linear velocity field and its gradient", "[transfer]", Order<1>, Order<2>,
                   Order<3>) {
  // The solver's own gather (eqs. 11-12) and velocity gradient (eq. 14), on the nodal field
  // v_I = A xi_I + b at the Greville points: B-splines reproduce linear functions with these
  // coefficients, so every particle must read A x_p + b and L_p = A, walls included. A is not
  // symmetric: a transposed L would fail.
  constexpr int P = TestType::value;
  auto sim = random_cloud<P>(9);
  auto& st = sim->state();
  sim->compute_weights();
  const int ny = st.grid.ny();
  Mat2 A;
  A << 0.3, -1.2, 0.7, 0.1;
  const Vec2 b(0.5, -0.25), c(-0.1, 0.4);
  GridLayer layer;
  layer.resize(st.grid.node_count());
  for (int i = 0; i < st.grid.nx(); ++i)
    for (int j = 0; j < ny; ++j) {
      layer.velocity[i * ny + j] = A * st.grid.greville(i, j) + b;
      layer.velocity_increment[i * ny + j] = A.transpose() * st.grid.greville(i, j) + c;
    }
  for (std::size_t p = 0; p < st.particles.size(); ++p) {
    const Vec2& x = st.particles.x[p];
    const GridVelocityAt g = gather_velocity<P>(st.weights[p], layer, ny);
    CHECK((g.velocity - (A * x + b)).norm() <= 1e-12);
    CHECK((g.increment - (A.transpose() * x + c)).norm() <= 1e-12);
    const Mat2 L = velocity_gradient<P>(st.weights[p], layer.velocity, ny);
    CHECK((L - A).norm() <= 1e-11);
  }
}

TEMPLATE_TEST_CASE("One step of a linear velocity field moves and deforms the particles exactly", "[transfer]",
                   Order<1>, Order<2>, Order<3>) {
  // The whole step (advance), not its parts: an unstressed elastic block on a uniform
  // lattice of 2 x 2 particles per cell, moving with v = A x + b, no forces. Around a
  // control point whose support lies inside the block the particles sit symmetrically, so
  // P2G gives v_I = A xi_I + b exactly; G2P then gives x_p + dt (A x_p + b), and the strain
  // update F = (I + dt L) I = I + dt A: the velocity gradient as the step itself applies it.
  constexpr int P = TestType::value;
  const double h = 0.1, dt = 1e-3;
  const int cells = 30, lo = 5, hi = 25;  // the block covers cells [5, 25) in x and y
  Mat2 A;
  A << 0.3, -1.2, 0.7, 0.1;
  const Vec2 b(0.5, -0.25);
  StepState<P> st = test::one_body_state(Grid<P>(Vec2(0.0, 0.0), Vec2(h, h), cells, cells), "block", ElasticSolid{},
                                         Vec2(h / 2, h / 2), [&](Particles& ps) {
                                           for (int i = 2 * lo; i < 2 * hi; ++i)
                                             for (int j = 2 * lo; j < 2 * hi; ++j) {
                                               const Vec2 x((i + 0.5) * h / 2, (j + 0.5) * h / 2);
                                               ps.push_back(x, 1.0, h * h / 4, 0);
                                               ps.v.back() = A * x + b;
                                             }
                                         });
  SolverSettings settings;
  settings.mass_cutoff_ratio = 0.0;
  const Particles before = st.particles;
  BsmpmSimulation<P> sim(std::move(st), settings, {}, {});
  sim.advance(dt);
  const Particles& ps = sim.particles();
  // Particles whose control points all have the full, symmetric lattice in their support:
  // P + 1 cells inside the block's edge is enough for every order.
  const double margin = (P + 1) * h;
  int checked = 0;
  for (std::size_t k = 0; k < before.size(); ++k) {
    const Vec2& x = before.x[k];
    if ((x.array() < lo * h + margin).any() || (x.array() > hi * h - margin).any()) continue;
    const std::size_t p = sim.index_of_id()[before.id[k]];
    INFO("particle at " << x.transpose());
    CHECK((ps.x[p] - (x + dt * (A * x + b))).norm() <= 1e-13);
    CHECK((ps.v[p] - (A * x + b)).norm() <= 1e-12);
    CHECK(((ps.F[p] - Mat2::Identity()) / dt - A).norm() <= 1e-9);
    ++checked;
  }
  CHECK(checked >= 100);
}

// The incompressible fluid's pressure projection on the grid (docs/method.md §12): the
// discrete divergence against fields whose divergence is known, the operator's symmetry and
// the one pressure mode it does not see, and a projection that the walls must stop.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "step/bsmpm_simulation.hpp"
#include "step/incompressible/excess_volume_filter.hpp"
#include "step/incompressible/fill_volume.hpp"
#include "step/incompressible/pressure_projection.hpp"
#include "unit/one_body_state.hpp"

using namespace bsmpm;

namespace {

// A 16 x 12 grid of 0.1 m cells; water on the lattice of 2 x 2 particles per cell over
// [0, width] x [0, 0.6] (touching the left wall and the floor, a free surface on top, and
// one to the right unless it fills the tank), the grid's weights and P2G done.
struct WaterBox {
  std::unique_ptr<BsmpmSimulation<2>> sim;
  StepState<2>& st() { return sim->state(); }
};

WaterBox water_box(int columns = 20) {
  const double h = 0.1, s = h / 2, V = s * s;
  IncompressibleFluid water;
  water.density = 1000.0;
  StepState<2> st = test::one_body_state(Grid<2>(Vec2(0.0, 0.0), Vec2(h, h), 16, 12), "water", water, Vec2(s, s),
                                         [&](Particles& ps) {
                                           for (int i = 0; i < columns; ++i)
                                             for (int j = 0; j < 12; ++j)
                                               ps.push_back(Vec2((i + 0.5) * s, (j + 0.5) * s), 1000.0 * V, V, 0);
                                         });
  WaterBox box{test::bare_simulation(std::move(st), SolverSettings{})};
  box.sim->compute_weights();
  box.sim->particle_to_grid();
  return box;
}

// D assembled from the box's particles, as the projection does it.
DivergenceOperator<2> divergence(StepState<2>& st) {
  DivergenceOperator<2> D;
  const PressureGrid grid(st.grid);
  D.resize(grid, st.grid.nx(), st.grid.ny());
  st.schedules[0].for_each([&](std::uint32_t p) {
    const auto& w = st.weights[p];
    D.add_particle(w, grid.at(st.particles.x[p], w.i0, w.j0), st.particles.volume(p), st.particles.volume0[p], 0.0, 0.0);
  });
  return D;
}

const NodeBox kAllVertices{0, 17, 0, 13};
const NodeBox kAllNodes{0, 18, 0, 14};

}  // namespace

TEST_CASE("The discrete divergence of a linear velocity field is its divergence times the water's hat volume",
          "[pressure]") {
  // B-splines reproduce linear fields with their Greville points, so at every particle the
  // interpolated field is the linear one and (D v)_K = div v sum_p V_p Q_K(x_p) exactly.
  auto box = water_box();
  auto& st = box.st();
  const DivergenceOperator<2> D = divergence(st);
  std::vector<Vec2> v(st.grid.node_count());
  for (int i = 0; i < st.grid.nx(); ++i)
    for (int j = 0; j < st.grid.ny(); ++j) {
      const Vec2 x = st.grid.greville(i, j);
      v[st.grid.index(i, j)] = Vec2(0.7 * x.x() - 0.3 * x.y(), 0.4 * x.x() + 1.3 * x.y());  // div = 2.0
    }
  double worst = 0.0, largest = 0.0;
  for (int K = 0; K < D.grid().count(); ++K) {
    const double volume = D.moments(K).volume;
    worst = std::max(worst, std::abs(D.row_times(K, v) - 2.0 * volume));
    largest = std::max(largest, 2.0 * volume);
  }
  REQUIRE(largest > 0.0);
  INFO("largest |D v - div v V_K| " << worst << " against " << largest);
  CHECK(worst <= 1e-13 * largest);
}

TEST_CASE("A uniform pressure pushes only where the water ends", "[pressure]") {
  // (D^T 1)_I = sum_p V_p grad S_I(x_p): the particles integrate grad S_I (piecewise linear)
  // exactly on their lattice, so it vanishes at every control point whose support lies in
  // the water (its integral is zero) and not at those its free surface cuts.
  auto box = water_box();
  auto& st = box.st();
  const DivergenceOperator<2> D = divergence(st);
  std::vector<double> ones(D.grid().count(), 1.0);
  double inside = 0.0, at_surface = 0.0;
  for (int i = 0; i < st.grid.nx(); ++i)
    for (int j = 0; j < st.grid.ny(); ++j) {
      const double f = D.transpose_at(ones, i, j).norm();
      // Control point i's support is cells [i - 2, i]: inside the water's 10 x 6 cells, off the walls' own points.
      if (i >= 1 && i <= 9 && j >= 1 && j <= 5) inside = std::max(inside, f);
      if (i == 11 || j == 7) at_surface = std::max(at_surface, f);
    }
  INFO("largest push inside " << inside << ", at the surface " << at_surface);
  CHECK(at_surface > 1e-3);
  CHECK(inside <= 1e-12 * at_surface);  // measured 2e-15 of it: round-off
}

TEST_CASE("The pressure operator is symmetric and positive, and its stabilization lifts the checkerboard only",
          "[pressure]") {
  auto box = water_box();
  auto& st = box.st();
  const DivergenceOperator<2> D = divergence(st);
  std::vector<std::uint8_t> fixed(st.grid.node_count(), 0);
  auto operator_with = [&](double stabilization) {
    PressureSystem<2> A;
    A.resize(D.grid(), st.grid.nx(), st.grid.ny());
    A.find_unknowns(D, kAllVertices, kAllNodes, 0.1, stabilization);
    A.set_weights(st.layers[0], fixed, 0.0);
    return A;
  };
  const PressureSystem<2> A = operator_with(0.05 / 1000.0), A0 = operator_with(0.0);
  const int n = A.size();
  REQUIRE(n > 50);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(n), y(n), Ax(n), Ay(n);
  for (int k = 0; k < n; ++k) {
    x[k] = u(rng);
    y[k] = u(rng);
  }
  A.apply(x, Ax);
  A.apply(y, Ay);
  INFO("x.Ay = " << x.dot(Ay) << ", y.Ax = " << y.dot(Ax));
  CHECK(std::abs(x.dot(Ay) - y.dot(Ax)) <= 1e-12 * std::abs(x.dot(Ax)));
  CHECK(x.dot(Ax) > 0.0);
  CHECK(y.dot(Ay) > 0.0);
  // The diagonal the preconditioner uses is the operator's.
  for (int k = 0; k < n; k += 7) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n), Ae(n);
    e[k] = 1.0;
    A.apply(e, Ae);
    CHECK(Ae[k] == Approx(A.diagonal()[k]).epsilon(1e-12));
  }
  // The vertex checkerboard (-1)^(a + b) is the mode D^T does not see away from the water's
  // edges (method.md §12): its Rayleigh quotient without S is far below a random field's;
  // S lifts it to the order of the rest, and leaves a linear field alone.
  Eigen::VectorXd z(n), linear(n), Az(n), Alin(n), A0lin(n);
  const int ny = D.grid().ny();
  for (int k = 0; k < n; ++k) {
    const int K = A.unknowns()[k], a = K / ny, b = K % ny;
    z[k] = (a + b) % 2 ? -1.0 : 1.0;
    linear[k] = 3.0 + 2.0 * a - 5.0 * b;
  }
  A0.apply(z, Az);
  const double checkerboard0 = z.dot(Az) / z.squaredNorm();
  A0.apply(x, Ax);
  const double random0 = x.dot(Ax) / x.squaredNorm();
  A.apply(z, Az);
  const double checkerboard = z.dot(Az) / z.squaredNorm();
  INFO("Rayleigh quotients: checkerboard " << checkerboard0 << " (with S " << checkerboard << "), random " << random0);
  CHECK(checkerboard0 < 0.05 * random0);
  CHECK(checkerboard > 0.3 * random0);
  A.apply(linear, Alin);
  A0.apply(linear, A0lin);
  CHECK((Alin - A0lin).norm() <= 1e-12 * A0lin.norm());
}

TEST_CASE("Projected, water falling on the floor stops and the floor takes its momentum", "[pressure]") {
  // Every node of water filling the tank's width moving down at 1 m/s: the velocity field of
  // incompressible water between walls with a free top that is closest to it is rest; the
  // floor takes the water's momentum (its impulse, recorded for the wall_reaction sensors),
  // the side walls push equally and oppositely.
  auto box = water_box(32);
  auto& st = box.st();
  st.dt = 1e-3;
  GridLayer& layer = st.layers[0];
  double momentum = 0.0;
  for (int n = 0; n < st.grid.node_count(); ++n) {
    if (!(layer.mass[n] > 0.0)) continue;
    layer.velocity[n] = Vec2(0.0, -1.0);
    momentum += layer.mass[n] * 1.0;
  }
  for (auto& side : st.diagnostics.wall_impulse) side.assign(std::max(st.grid.nx(), st.grid.ny()), Vec2::Zero());
  PressureParameters parameters;
  parameters.tolerance = 1e-10;
  parameters.max_iterations = 2000;
  auto projection = PressureProjection<2>::create(parameters, st);
  REQUIRE(projection);
  projection->project_velocity(st);
  double kept = 0.0, floor = 0.0, sides = 0.0, push = 0.0;
  for (int n = 0; n < st.grid.node_count(); ++n) kept -= layer.mass[n] * layer.velocity[n].y();
  for (const Vec2& I : st.diagnostics.wall_impulse[kBottom]) floor += I.y();
  for (const int side : {kLeft, kRight})
    for (const Vec2& I : st.diagnostics.wall_impulse[side]) {
      sides += I.x();
      push += std::abs(I.x());
    }
  INFO("the water keeps " << kept << " N s/m of " << momentum << "; the floor takes " << floor << "; side walls "
                          << sides << " (each " << push / 2 << "); " << st.diagnostics.pressure.iterations
                          << " iterations");
  CHECK(st.diagnostics.pressure.residual <= 1e-10);
  // Measured 4.2e-4 of the momentum kept, by the light control points above the surface
  // (their supports barely reach the water: no unknown vertex holds them); bound 1e-3.
  CHECK(std::abs(kept) <= 1e-3 * momentum);
  CHECK(floor + kept == Approx(momentum).epsilon(1e-12));  // what the floor takes, the water loses
  CHECK(push > 0.1 * momentum);               // the water presses on the side walls ...
  // ... equally: to the solve's tolerance (1e-10 here), not to round-off, since the incomplete
  // Cholesky factor's natural ordering is not mirror-symmetric. Measured 1.2e-9 N s/m (1.2e-12
  // of the momentum; with Jacobi's preconditioner alone round-off, below 1e-12); bound 1e-11.
  CHECK(std::abs(sides) <= 1e-11 * momentum);
}


TEST_CASE("The assembled pressure matrix is the matrix-free operator", "[pressure]") {
  // The solve's incomplete Cholesky preconditioner factors A assembled (method.md §12): it must
  // be the operator the matrix-free product applies, walls and stabilization included.
  auto box = water_box(24);
  auto& st = box.st();
  const DivergenceOperator<2> D = divergence(st);
  std::vector<std::uint8_t> fixed(st.grid.node_count(), 0);
  const int ny = st.grid.ny();
  for (int i = 0; i < st.grid.nx(); ++i) fixed[i * ny] |= kFixedY;  // the floor holds v_y
  for (int j = 0; j < ny; ++j) fixed[j] |= kFixedX;                 // the left wall holds v_x
  PressureSystem<2> A;
  A.resize(D.grid(), st.grid.nx(), st.grid.ny());
  A.find_unknowns(D, kAllVertices, kAllNodes, 0.1, 0.05 / 1000.0);
  A.set_weights(st.layers[0], fixed, 0.0);
  Eigen::SparseMatrix<double, Eigen::RowMajor> M;
  A.assemble(M);
  const int n = A.size();
  REQUIRE(M.rows() == n);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(n), Ax(n);
  for (int k = 0; k < n; ++k) x[k] = u(rng);
  A.apply(x, Ax);
  const Eigen::VectorXd Mx = M * x;
  INFO("|Mx - Ax| = " << (Mx - Ax).norm() << ", |Ax| = " << Ax.norm());
  CHECK((Mx - Ax).norm() <= 1e-12 * Ax.norm());
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Mt = M.transpose();
  CHECK((M - Mt).norm() <= 1e-12 * M.norm());
}

TEST_CASE("J from the hats' fill is 1 on the seeding's lattice and the packing's ratio where the particles crowd",
          "[pressure]") {
  // method.md §12, "The water's volume" (solver.pressure.volume_measure = "fill"): the hat
  // summed over a lattice of spacing h/2 is 2 per axis at any offset, walls included, so the
  // seeded water has J = 1 to round-off, at its free surface too; pressed to 0.8 of its
  // width, it has 1.25 times the particles per hat and J = 0.8 inside (the hat sampled at
  // 0.4 h: within 2 %), and no particle gets J > 1 where the surface cuts the hats.
  auto box = water_box();
  auto& st = box.st();
  FillVolume<2> fill;
  fill.resize(PressureGrid(st.grid));
  fill.apply(st, {0}, kAllVertices);
  double worst = 0.0;
  for (std::size_t p = 0; p < st.particles.size(); ++p) worst = std::max(worst, std::abs(st.particles.J[p] - 1.0));
  INFO("largest |J - 1| on the lattice " << worst);
  CHECK(worst <= 1e-14);

  for (std::size_t p = 0; p < st.particles.size(); ++p) st.particles.x[p].x() *= 0.8;
  box.sim->compute_weights();
  fill.apply(st, {0}, kAllVertices);
  double inside = 0.0, highest = 0.0;
  int n = 0;
  for (std::size_t p = 0; p < st.particles.size(); ++p) {
    const Vec2& x = st.particles.x[p];
    highest = std::max(highest, st.particles.J[p]);
    if (x.x() < 0.55 && x.y() > 0.1 && x.y() < 0.45) {
      inside += st.particles.J[p];
      ++n;
    }
  }
  inside /= n;
  INFO("mean J inside " << inside << " over " << n << " particles; largest J " << highest);
  CHECK(n > 50);
  CHECK(std::abs(inside - 0.8) <= 0.02 * 0.8);
  CHECK(highest <= 1.0);
}

// eq. I3f (method.md §12): one pass of the excess volume's filter is [1 2 1] / 4 per axis
// between full hats, keeps the total, removes the vertex-to-vertex alternation and leaves
// the vertices whose hats are less than half full alone.
TEST_CASE("The excess volume's filter keeps the total, removes the alternation and spares part-filled hats",
          "[pressure]") {
  Grid<2> grid(Vec2(0.0, 0.0), Vec2(0.1, 0.1), 10, 8);
  const PressureGrid hats(grid);
  const int nx = hats.nx(), ny = hats.ny();
  const NodeBox box{0, nx, 0, ny};
  ExcessVolumeFilter filter;
  filter.resize(hats);
  // Full hats everywhere but the top row of vertices (a free surface: a quarter full).
  auto volume0 = [&](int K) {
    const int a = K / ny, b = K % ny;
    return (b == ny - 1 ? 0.25 : 1.0) * hats.hat_integral(a, b);
  };
  auto total = [&](auto&& e) {
    double sum = 0.0;
    for (int K = 0; K < hats.count(); ++K) sum += e(K);
    return sum;
  };

  SECTION("a spike spreads as [1 2 1] / 4 along each axis") {
    const int K0 = 4 * ny + 3;
    filter.apply(box, 1, volume0, [&](int K) { return K == K0 ? 16.0 : 0.0; });
    CHECK(filter.excess(K0) == Approx(4.0));
    CHECK(filter.excess(K0 + 1) == Approx(2.0));
    CHECK(filter.excess(K0 - ny) == Approx(2.0));
    CHECK(filter.excess(K0 + ny + 1) == Approx(1.0));
    CHECK(filter.excess(K0 + 2) == 0.0);
    CHECK(total([&](int K) { return filter.excess(K); }) == Approx(16.0).epsilon(1e-14));
  }
  SECTION("the alternation between full hats is removed, the part-filled row untouched") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(-0.1, 0.1);
    std::vector<double> e(hats.count());
    for (int a = 0; a < nx; ++a)
      for (int b = 0; b < ny; ++b) e[a * ny + b] = ((a + b) % 2 ? 1.0 : -1.0) + noise(rng);
    filter.apply(box, 2, volume0, [&](int K) { return e[K]; });
    CHECK(total([&](int K) { return filter.excess(K); }) == Approx(total([&](int K) { return e[K]; })).margin(1e-12));
    for (int a = 0; a < nx; ++a) {
      CHECK(filter.excess(a * ny + ny - 1) == e[a * ny + ny - 1]);  // less than half full: not exchanged
      // Interior vertices away from the walls and the surface: the +-1 alternation is gone,
      // the noise (at most 0.1) averaged.
      if (a >= 2 && a < nx - 2)
        for (int b = 2; b < ny - 3; ++b) CHECK(std::abs(filter.excess(a * ny + b)) < 0.1);
    }
  }
}

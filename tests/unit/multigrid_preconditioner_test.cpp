// The pressure solve's multigrid preconditioner (docs/method.md §12, "The solve") on the
// assembled pressure matrix of a water box: a symmetric positive definite V-cycle (CG needs
// one), iterations that do not grow as the grid is refined, and the solution incomplete
// Cholesky's CG finds.
#include <catch2/catch.hpp>

#include <random>

#include "step/bsmpm_simulation.hpp"
#include "step/incompressible/multigrid_preconditioner.hpp"
#include "step/incompressible/pressure_system.hpp"
#include "unit/one_body_state.hpp"

using namespace bsmpm;

namespace {

using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// A tank of 1.2 x 0.8 m in cells of h, water over [0, 0.75] x [0, 0.5] against the left
// wall and the floor (which hold v_x and v_y), 2 x 2 particles a cell; A assembled as the
// projection does it.
struct System {
  std::unique_ptr<BsmpmSimulation<2>> sim;
  DivergenceOperator<2> D;
  PressureSystem<2> A;
  RowMatrix M;
};

// With `spray`, drops of one cell (2 x 2 particles) and a ligament of single cells on a
// diagonal above the water: thin water whose alternating pressure modes A barely sees.
std::unique_ptr<System> water_tank(double h, bool spray = false) {
  const double s = h / 2, V = s * s;
  IncompressibleFluid water;
  water.density = 1000.0;
  const int cx = static_cast<int>(std::lround(1.2 / h)), cy = static_cast<int>(std::lround(0.8 / h));
  const int px = static_cast<int>(std::lround(0.75 / s)), py = static_cast<int>(std::lround(0.5 / s));
  auto system = std::make_unique<System>();
  StepState<2> st0 = test::one_body_state(Grid<2>(Vec2(0.0, 0.0), Vec2(h, h), cx, cy), "water", water, Vec2(s, s),
                                          [&](Particles& ps) {
                                            for (int i = 0; i < px; ++i)
                                              for (int j = 0; j < py; ++j)
                                                ps.push_back(Vec2((i + 0.5) * s, (j + 0.5) * s), 1000.0 * V, V, 0);
                                            if (!spray) return;
                                            auto cell = [&](double x, double y) {  // the cell whose corner is (x, y)
                                              const double x0 = std::floor(x / h) * h, y0 = std::floor(y / h) * h;
                                              for (int i = 0; i < 2; ++i)
                                                for (int j = 0; j < 2; ++j)
                                                  ps.push_back(Vec2(x0 + (i + 0.5) * s, y0 + (j + 0.5) * s), 1000.0 * V, V, 0);
                                            };
                                            for (double x : {0.85, 0.95, 1.05}) cell(x, 0.62);  // drops
                                            for (int k = 0; k < 6; ++k) cell(0.3 + k * h, 0.58 + k * h);  // a ligament
                                          });
  system->sim = test::bare_simulation(std::move(st0), SolverSettings{});
  system->sim->compute_weights();
  system->sim->particle_to_grid();
  StepState<2>& st = system->sim->state();
  const PressureGrid grid(st.grid);
  system->D.resize(grid, st.grid.nx(), st.grid.ny());
  st.schedules[0].for_each([&](std::uint32_t p) {
    const auto& w = st.weights[p];
    system->D.add_particle(w, grid.at(st.particles.x[p], w.i0, w.j0), st.particles.volume(p), st.particles.volume0[p],
                           0.0, 0.0);
  });
  std::vector<std::uint8_t> fixed(st.grid.node_count(), 0);
  const int ny = st.grid.ny();
  for (int i = 0; i < st.grid.nx(); ++i) fixed[i * ny] |= kFixedY;
  for (int j = 0; j < ny; ++j) fixed[j] |= kFixedX;
  system->A.resize(grid, st.grid.nx(), st.grid.ny());
  system->A.find_unknowns(system->D, NodeBox{0, grid.nx(), 0, grid.ny()}, NodeBox{0, st.grid.nx(), 0, st.grid.ny()},
                          0.1, 0.05 / 1000.0);
  system->A.set_weights(st.layers[0], fixed, 0.0);
  system->A.assemble(system->M);
  return system;
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (int k = 0; k < n; ++k) x[k] = u(rng);
  return x;
}

using MultigridCG = Eigen::ConjugateGradient<RowMatrix, Eigen::Lower | Eigen::Upper, MultigridPreconditioner>;
using CholeskyCG = Eigen::ConjugateGradient<RowMatrix, Eigen::Lower | Eigen::Upper,
                                            Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>>>;

// x.M^-1 y = y.M^-1 x to round-off (bound 1e-12 relative) and x.M^-1 x > 0 for two random
// vectors x (seed 3) and y (seed 5); returns M^-1 x.
Eigen::VectorXd check_symmetric_positive(const MultigridPreconditioner& M, int n) {
  const Eigen::VectorXd x = random_vector(n, 3), y = random_vector(n, 5);
  const Eigen::VectorXd Mx = M.solve(x), My = M.solve(y);
  INFO("x.M^-1 y - y.M^-1 x = " << x.dot(My) - y.dot(Mx) << " against |M^-1 x| |y| = " << Mx.norm() * y.norm());
  CHECK(std::abs(x.dot(My) - y.dot(Mx)) <= 1e-12 * Mx.norm() * y.norm());
  CHECK(x.dot(Mx) > 0.0);
  CHECK(y.dot(My) > 0.0);
  return Mx;
}

}  // namespace

TEST_CASE("The multigrid V-cycle is a symmetric positive definite operator", "[pressure][multigrid]") {
  auto tank = water_tank(0.025);
  const int n = tank->A.size();
  MultigridPreconditioner M;
  M.set_coarsest(60);  // several levels on this small system
  M.set_vertices(tank->A.grid().nx(), tank->A.grid().ny(), tank->A.unknowns());
  M.compute(tank->M);
  REQUIRE(M.info() == Eigen::Success);
  INFO(n << " unknowns, " << M.levels() << " levels");
  REQUIRE(M.levels() >= 3);
  // Forward Gauss-Seidel before the coarse correction, backward after: symmetric but for
  // round-off (measured 1.4e-17 relative).
  const Eigen::VectorXd x = random_vector(n, 3);
  const Eigen::VectorXd Mx = check_symmetric_positive(M, n);
  // The same bits on a second application (the levels' storage is reused).
  CHECK((M.solve(x) - Mx).norm() == 0.0);
}

TEST_CASE("Multigrid CG iterations do not grow as the grid is refined and give incomplete Cholesky's solution",
          "[pressure][multigrid]") {
  std::vector<int> multigrid, cholesky;
  for (double h : {0.05, 0.025, 0.0125}) {
    auto tank = water_tank(h);
    const int n = tank->A.size();
    const Eigen::VectorXd b = tank->M * random_vector(n, 7);
    MultigridCG mg;
    mg.setTolerance(1e-10);
    mg.setMaxIterations(500);
    mg.preconditioner().set_coarsest(60);
    mg.preconditioner().set_vertices(tank->A.grid().nx(), tank->A.grid().ny(), tank->A.unknowns());
    mg.compute(tank->M);
    const Eigen::VectorXd p = mg.solve(b);
    REQUIRE(mg.info() == Eigen::Success);
    CholeskyCG ic;
    ic.setTolerance(1e-10);
    ic.setMaxIterations(500);
    ic.compute(tank->M);
    const Eigen::VectorXd q = ic.solve(b);
    REQUIRE(ic.info() == Eigen::Success);
    multigrid.push_back(static_cast<int>(mg.iterations()));
    cholesky.push_back(static_cast<int>(ic.iterations()));
    INFO("h = " << h << ": " << n << " unknowns, " << mg.preconditioner().levels() << " levels, multigrid "
                << mg.iterations() << " iterations, incomplete Cholesky " << ic.iterations() << "; |p - q| / |q| = "
                << (p - q).norm() / q.norm());
    // Both to a relative residual of 1e-10: the solutions agree to the condition number
    // times that (measured 4e-11, 1.5e-10, 7e-10); bound 1e-7.
    CHECK((p - q).norm() <= 1e-7 * q.norm());
  }
  INFO("multigrid " << multigrid[0] << ", " << multigrid[1] << ", " << multigrid[2] << " iterations; incomplete Cholesky "
                    << cholesky[0] << ", " << cholesky[1] << ", " << cholesky[2]);
  // Measured: multigrid 6, 6, 6; incomplete Cholesky 8, 12, 20 (growing as 1/h). Bound:
  // multigrid's at the finest at most 2 more than at the coarsest, and fewer than half of
  // incomplete Cholesky's there.
  CHECK(multigrid[2] <= multigrid[0] + 2);
  CHECK(2 * multigrid[2] < cholesky[2]);
}

TEST_CASE("The multigrid solves thin water's unknowns together: drops and ligaments cost no extra iterations",
          "[pressure][multigrid]") {
  // The thin block is part of the symmetric smoother: the cycle stays symmetric positive definite.
  auto spray = water_tank(0.025, true);
  const int n = spray->A.size();
  MultigridPreconditioner M;
  M.set_coarsest(60);
  M.set_thin_rows(21);  // three of the seven vertex lines of a full row (P = 2)
  M.set_vertices(spray->A.grid().nx(), spray->A.grid().ny(), spray->A.unknowns());
  M.compute(spray->M);
  REQUIRE(M.info() == Eigen::Success);
  INFO(n << " unknowns, " << M.thin_unknowns() << " thin");
  REQUIRE(M.thin_unknowns() > 0);
  // Measured 4.8e-17 relative.
  check_symmetric_positive(M, n);

  auto iterations = [](System& system, int thin_rows, Eigen::VectorXd* p = nullptr) {
    const int n = system.A.size();
    const Eigen::VectorXd b = system.M * random_vector(n, 7);
    MultigridCG mg;
    mg.setTolerance(1e-10);
    mg.setMaxIterations(500);
    mg.preconditioner().set_coarsest(60);
    mg.preconditioner().set_thin_rows(thin_rows);
    mg.preconditioner().set_vertices(system.A.grid().nx(), system.A.grid().ny(), system.A.unknowns());
    mg.compute(system.M);
    const Eigen::VectorXd x = mg.solve(b);
    REQUIRE(mg.info() == Eigen::Success);
    if (p) *p = x;
    return static_cast<int>(mg.iterations());
  };
  auto tank = water_tank(0.025);
  Eigen::VectorXd with, without;
  const int plain = iterations(*tank, 21), point = iterations(*spray, 0, &without), block = iterations(*spray, 21, &with);
  INFO("the tank " << plain << " iterations; with spray " << point << " with the point smoother alone, " << block
                   << " with the thin block; |p_block - p_point| / |p_point| = " << (with - without).norm() / without.norm());
  // Measured: the tank 6 (no row is short there), with spray 24 -> 6. Bound: the spray costs at
  // most 2 more than the tank, and the thin block at least halves the point smoother's count.
  CHECK(block <= plain + 2);
  CHECK(2 * block <= point);
  // Both solutions to a relative residual of 1e-10 (measured 8.8e-11 apart); bound 1e-6.
  CHECK((with - without).norm() <= 1e-6 * without.norm());
}

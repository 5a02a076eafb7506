// The incompressible fluid's pressure (docs/method.md §12): a fractional step after
// Chorin, as Kularathna & Soga (2017) carry it to MPM. The explicit step is the predictor
// (gravity, the viscous stress, the walls and their skin friction, without pressure); this
// effect then projects the constrained nodal velocity v* of each field that holds the
// fluid onto the velocities whose water keeps its volume,
//
//   v = v* + dt W D^T p,   (D W D^T + alpha/rho0 S) p = -(D v* + beta e / dt) / dt,
//
// (eqs. I1-I4), gives every fluid particle the pressure p(x_p) = sum_K Q_K(x_p) p_K and
// records on the walls the pressure's push they hold back (the wall_reaction sensors).
#pragma once

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>

#include "core/boundaries.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "step/effect.hpp"
#include "step/incompressible/divergence_operator.hpp"
#include "step/incompressible/excess_volume_filter.hpp"
#include "step/incompressible/fill_volume.hpp"
#include "step/incompressible/jacobi_preconditioner.hpp"
#include "step/incompressible/multigrid_preconditioner.hpp"
#include "step/incompressible/pressure_parameters.hpp"
#include "step/incompressible/pressure_system.hpp"

namespace bsmpm {

template <int P>
class PressureProjection final : public EffectBase<PressureProjection<P>, P> {
 public:
  using Parameters = PressureParameters;
  static constexpr EffectPhase kPhase = EffectPhase::kProjection;

  static std::unique_ptr<Effect<P>> create(const Parameters& p, const StepState<P>& st) {
    std::vector<Field> fields;
    for (std::size_t b = 0; b < st.bodies.size(); ++b) {
      if (!is_incompressible(st.bodies[b].material)) continue;
      const int layer = st.bodies[b].layer;
      auto it = std::find_if(fields.begin(), fields.end(), [&](const Field& f) { return f.layer == layer; });
      if (it == fields.end()) it = fields.insert(fields.end(), Field{layer, {}});
      it->bodies.push_back(static_cast<int>(b));
    }
    if (fields.empty()) return nullptr;
    return std::make_unique<PressureProjection>(p, std::move(fields), st.grid);
  }

  struct Field {
    int layer;
    std::vector<int> bodies;  // the incompressible bodies in it
  };

  PressureProjection(const Parameters& p, std::vector<Field> fields, const Grid<P>& grid)
      : parameters_(p), fields_(std::move(fields)), grid_(grid) {
    const int nx = grid.nx(), ny = grid.ny();
    D_.resize(grid_, nx, ny);
    if (p.volume_measure == PressureParameters::VolumeMeasure::kFill) fill_.resize(grid_);
    if (p.volume_correction_filter > 0) filter_.resize(grid_);
    system_.resize(grid_, nx, ny);
    pressure_.assign(grid_.count(), 0.0);
    last_.assign(fields_.size(), std::vector<double>(grid_.count(), std::nan("")));
    force_.assign(std::size_t(nx) * ny, Vec2::Zero());
    // The components the walls hold (method.md §3): the normal one on a symmetry wall, both
    // on a no-slip wall, always; the normal one on a slip wall while the water presses on it
    // (decided each step, hold_slip_walls).
    base_fixed_.assign(std::size_t(nx) * ny, 0);
    slip_.assign(std::size_t(nx) * ny, 0);
    auto wall = [&](int i, int j, int side, std::uint8_t normal) {
      const std::size_t n = std::size_t(i) * ny + j;
      switch (p.walls[side]) {
        case WallKind::kSlip: slip_[n] |= normal; break;
        case WallKind::kSymmetry: base_fixed_[n] |= normal; break;
        case WallKind::kNoSlip: base_fixed_[n] |= kFixedX | kFixedY; break;
      }
    };
    for (int j = 0; j < ny; ++j) {
      wall(0, j, kLeft, kFixedX);
      wall(nx - 1, j, kRight, kFixedX);
    }
    for (int i = 0; i < nx; ++i) {
      wall(i, 0, kBottom, kFixedY);
      wall(i, ny - 1, kTop, kFixedY);
    }
    fixed_ = base_fixed_;
    // The multigrid's thin unknowns (method.md §12, "The solve"): rows that reach at most three
    // of the 2P + 3 vertex lines a full row reaches, i.e. water at most about three vertices thick.
    constexpr int kReach = 2 * DivergenceOperator<P>::kSpan - 1;
    multigrid_cg_.preconditioner().set_thin_rows(3 * kReach);
    multigrid_cg_.preconditioner().set_reach(DivergenceOperator<P>::kSpan - 1);
  }

  std::string describe() const override {
    return format("pressure projection (incompressible, method.md §12): pressure on the cell corners, CG to %g "
                  "(at most %d iterations, preconditioned by %s), volume correction %g (J %s, %d filter passes), "
                  "stabilization %g, p = 0 below fill %g",
                  parameters_.tolerance, parameters_.max_iterations,
                  parameters_.preconditioner == PressurePreconditioner::kMultigrid ? "multigrid" : "incomplete Cholesky",
                  parameters_.volume_correction,
                  parameters_.volume_measure == PressureParameters::VolumeMeasure::kFill ? "from the hats' fill"
                                                                                          : "carried",
                  parameters_.volume_correction_filter, parameters_.stabilization, parameters_.surface_fraction);
  }

  void project_velocity(StepState<P>& st) override {
    for (const Field& f : fields_) project_field(st, f);
  }

  // The last solve's pressure, from which the next one starts: state a checkpoint holds.
  void save_state(std::vector<double>& out) const override {
    for (const auto& last : last_) out.insert(out.end(), last.begin(), last.end());
  }
  std::size_t load_state(const std::vector<double>& in, std::size_t at) override {
    for (auto& last : last_) {
      if (at + last.size() > in.size()) throw std::invalid_argument("restore: the pressure state is not of this scene");
      std::copy(in.begin() + at, in.begin() + at + last.size(), last.begin());
      at += last.size();
    }
    return at;
  }

 private:
  void project_field(StepState<P>& st, const Field& field) {
    GridLayer& layer = st.layers[field.layer];
    if (layer.active.empty()) return;
    const NodeBox nodes = layer.active;
    // The vertices of the cells the particles are in: cells [i0, i1 - P - 1], corners one more.
    const NodeBox vertices{nodes.i0, nodes.i1 - P + 1, nodes.j0, nodes.j1 - P + 1};
    const double dt = st.dt;
    auto& ps = st.particles;

    // J from the hats' fill (method.md §12, "What J measures", eq. I5), before eq. I2 reads it.
    if (parameters_.volume_measure == PressureParameters::VolumeMeasure::kFill) fill_.apply(st, field.bodies, vertices);
    // eq. I2: D, the volume fractions, the excess volume and the particles' pressure moments.
    for (int b : field.bodies) {
      st.schedules[b].for_each([&](std::uint32_t p) {
        const auto& w = st.weights[p];
        const PressureGrid::Hats q = grid_.at(ps.x[p], w.i0, w.j0);
        D_.add_particle(w, q, ps.volume(p), ps.volume0[p], ps.volume0[p] * (ps.J[p] - 1.0), ps.pressure[p]);
      });
    }
    system_.find_unknowns(D_, vertices, nodes, parameters_.surface_fraction,
                          parameters_.stabilization / parameters_.density);
    const int n = system_.size();
    const auto& unknowns = system_.unknowns();
    Eigen::VectorXd rhs(n), guess(n);
    // The warm start: the last step's pressure where there was one (the solve's state, held
    // by a checkpoint), else the particles' pressure projected onto the hats (at the start,
    // and where the water has just arrived).
    std::vector<double>& last = last_[&field - fields_.data()];
    for (int k = 0; k < n; ++k) {
      const int K = unknowns[k];
      const auto& m = D_.moments(K);
      guess[k] = std::isnan(last[K]) ? m.pressure / m.volume : last[K];
    }
    std::fill(pressure_.begin(), pressure_.end(), 0.0);
    for (int k = 0; k < n; ++k) pressure_[unknowns[k]] = guess[k];
    hold_slip_walls(st, layer, nodes);
    system_.set_weights(layer, fixed_, st.mass_cutoff);
    // eq. I3f: the excess volume filtered between full hats (none without the option).
    const bool filtered = parameters_.volume_correction_filter > 0;
    if (filtered)
      filter_.apply(vertices, parameters_.volume_correction_filter, [&](int K) { return D_.moments(K).volume0; },
                    [&](int K) { return D_.moments(K).excess; });
    // eq. I4's right-hand side.
#pragma omp parallel for schedule(static) if (n > 4096)
    for (int k = 0; k < n; ++k) {
      const int K = unknowns[k];
      const double excess = filtered ? filter_.excess(K) : D_.moments(K).excess;
      rhs[k] = -(D_.row_times(K, layer.velocity) + parameters_.volume_correction * excess / dt) / dt;
    }
    PressureSolve solve;
    solve.unknowns = n;
    std::fill(pressure_.begin(), pressure_.end(), 0.0);
    if (n > 0) {
      const PressureMatrix<P> A(&system_);
      Eigen::VectorXd p;
      bool converged = false;
      auto run = [&](auto& cg, const auto& matrix) {
        cg.setTolerance(parameters_.tolerance);
        cg.setMaxIterations(parameters_.max_iterations);
        cg.compute(matrix);
        p = cg.solveWithGuess(rhs, guess);
        solve.iterations = static_cast<int>(cg.iterations());
        solve.residual = cg.error();
        converged = cg.info() == Eigen::Success;
      };
      // Conjugate gradients preconditioned by an incomplete Cholesky factor of A assembled (a
      // sixth of the iterations Jacobi takes); where it does not converge (measured: 7 of 947
      // solves of the Lobovsky tank at 8 mm, at impacts) the matrix-free solve with Jacobi's
      // preconditioner starts again from the warm start.
      system_.assemble(assembled_);
      if (parameters_.preconditioner == PressurePreconditioner::kMultigrid) {
        multigrid_cg_.preconditioner().set_vertices(grid_.nx(), grid_.ny(), unknowns);
        run(multigrid_cg_, assembled_);
      } else {
        run(ic_cg_, assembled_);
      }
      const int preconditioned = solve.iterations;
      int jacobi = 0;
      if (!converged || !p.allFinite()) {
        run(cg_, A);
        jacobi = solve.iterations;
        solve.iterations += preconditioned;
      }
      if (!converged || !p.allFinite())
        throw NumericalError(format(
            "numerical instability at step %ld (t = %.6g s): the pressure solve of the incompressible fluid did not "
            "converge: relative residual %.3g after %d conjugate-gradient iterations preconditioned by %s "
            "and %d by Jacobi, above solver.pressure.tolerance = %g (%d unknowns); reduce the time step "
            "(time.cfl) or raise solver.pressure.max_iterations",
            st.step, st.time, solve.residual, preconditioned,
            parameters_.preconditioner == PressurePreconditioner::kMultigrid ? "multigrid" : "incomplete Cholesky",
            jacobi, parameters_.tolerance, n));
      for (int k = 0; k < n; ++k) pressure_[unknowns[k]] = p[k];
    }
    st.diagnostics.pressure = solve;
    std::fill(last.begin(), last.end(), std::nan(""));
    for (int K : unknowns) last[K] = pressure_[K];

    // eq. I1: the correction, and on the walls the push they hold back.
    system_.pressure_force(pressure_, force_);
    const int nx = grid_.nx() + P - 1, ny = grid_.ny() + P - 1;  // control points per axis
    auto& impulse = st.diagnostics.wall_impulse;
    const double cut = st.mass_cutoff;
    system_.for_each_node([&](int node, int, int) {
      if (layer.mass[node] > cut) layer.velocity[node] += dt * force_[node].cwiseProduct(system_.inverse_mass(node));
    });
    // What each wall did to its control point: held back the pressure's push on a held
    // component; stopped a slip wall's free component that the pressure turned into the wall.
    auto hold = [&](int node, int side, int k, bool corner) {
      const double m = layer.mass[node];
      if (!(m > cut)) return;
      const int axis = side == kLeft || side == kRight ? 0 : 1;
      const double outward = side == kLeft || side == kBottom ? -1.0 : 1.0;
      const std::uint8_t bit = axis == 0 ? kFixedX : kFixedY;
      Vec2 taken = Vec2::Zero();
      if (fixed_[node] & bit) {
        taken[axis] = -dt * force_[node][axis];
      } else if (slip_[node] & bit && layer.velocity[node][axis] * outward > 0.0) {
        taken[axis] = -m * layer.velocity[node][axis];
        layer.velocity[node][axis] = 0.0;
      }
      // A no-slip wall holds the tangential component too (at a corner, the other wall's normal).
      if (parameters_.walls[side] == WallKind::kNoSlip && !corner) taken[1 - axis] = -dt * force_[node][1 - axis];
      impulse[side][k] += taken;
    };
    if (nodes.i0 == 0) for (int j = nodes.j0; j < nodes.j1; ++j) hold(j, kLeft, j, j == 0 || j == ny - 1);
    if (nodes.i1 == nx)
      for (int j = nodes.j0; j < nodes.j1; ++j) hold((nx - 1) * ny + j, kRight, j, j == 0 || j == ny - 1);
    if (nodes.j0 == 0) for (int i = nodes.i0; i < nodes.i1; ++i) hold(i * ny, kBottom, i, i == 0 || i == nx - 1);
    if (nodes.j1 == ny)
      for (int i = nodes.i0; i < nodes.i1; ++i) hold(i * ny + ny - 1, kTop, i, i == 0 || i == nx - 1);

    // The particles' pressure, p(x_p) = sum_K Q_K(x_p) p_K, for the stress output and probes.
    for (int b : field.bodies) {
      const Body& body = st.bodies[b];
#pragma omp parallel for schedule(static)
      for (long p = static_cast<long>(body.begin); p < static_cast<long>(body.end); ++p) {
        const auto& w = st.weights[p];
        ps.pressure[p] = grid_.interpolate(grid_.at(ps.x[p], w.i0, w.j0), pressure_, grid_.index(w.i0, w.j0));
      }
    }
    D_.clear(vertices);
  }

  // A slip wall holds its control point's normal component in the projection where the
  // water presses on it: where the predictor's velocity plus the push of the warm start's
  // pressure (this step's estimate of p) points into the wall. Elsewhere the component is
  // free, so that the pressure can pull water back onto the wall as well as let it go; a
  // free component the solve turns into the wall is stopped afterwards (project_field).
  // A held component that the predictor had released is brought to rest here.
  void hold_slip_walls(StepState<P>& st, GridLayer& layer, const NodeBox& nodes) {
    fixed_ = base_fixed_;
    const int nx = grid_.nx() + P - 1, ny = grid_.ny() + P - 1;
    auto& impulse = st.diagnostics.wall_impulse;
    auto decide = [&](int i, int j, int side, int k) {
      const int node = i * ny + j;
      const int axis = side == kLeft || side == kRight ? 0 : 1;
      const std::uint8_t bit = axis == 0 ? kFixedX : kFixedY;
      if (!(slip_[node] & bit)) return;
      const double m = layer.mass[node];
      if (!(m > st.mass_cutoff)) return;
      const double outward = side == kLeft || side == kBottom ? -1.0 : 1.0;
      const Vec2 push = D_.transpose_at(pressure_, i, j);
      if ((m * layer.velocity[node][axis] + st.dt * push[axis]) * outward < 0.0) return;  // leaves the wall
      fixed_[node] |= bit;
      impulse[side][k][axis] -= m * layer.velocity[node][axis];
      layer.velocity[node][axis] = 0.0;
    };
    if (nodes.i0 == 0) for (int j = nodes.j0; j < nodes.j1; ++j) decide(0, j, kLeft, j);
    if (nodes.i1 == nx) for (int j = nodes.j0; j < nodes.j1; ++j) decide(nx - 1, j, kRight, j);
    if (nodes.j0 == 0) for (int i = nodes.i0; i < nodes.i1; ++i) decide(i, 0, kBottom, i);
    if (nodes.j1 == ny) for (int i = nodes.i0; i < nodes.i1; ++i) decide(i, ny - 1, kTop, i);
  }

  Parameters parameters_;
  std::vector<Field> fields_;
  Eigen::ConjugateGradient<PressureMatrix<P>, Eigen::Lower | Eigen::Upper, JacobiPreconditioner<P>> cg_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> assembled_;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double, Eigen::RowMajor>, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>>> ic_cg_;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double, Eigen::RowMajor>, Eigen::Lower | Eigen::Upper,
                           MultigridPreconditioner> multigrid_cg_;
  PressureGrid grid_;
  DivergenceOperator<P> D_;
  FillVolume<P> fill_;                    // only with volume_measure = "fill"
  ExcessVolumeFilter filter_;             // only with volume_correction_filter > 0
  PressureSystem<P> system_;
  std::vector<std::vector<double>> last_;  // per field: the last solve's p_K, NaN off its unknowns
  std::vector<double> pressure_;         // p_K on every vertex (0 off the unknowns)
  std::vector<Vec2> force_;              // D^T p on the control points
  std::vector<std::uint8_t> base_fixed_; // per control point: the components the walls always hold
  std::vector<std::uint8_t> slip_;       // per control point: its normal component on a slip wall
  std::vector<std::uint8_t> fixed_;      // this step's: base_fixed_ and the slip walls that hold
};

}  // namespace bsmpm

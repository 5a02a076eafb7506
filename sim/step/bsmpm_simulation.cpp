#include "step/bsmpm_simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/error.hpp"
#include "core/format.hpp"
#include "step/grid_to_particle.hpp"

namespace bsmpm {

namespace {

// Fastest signal c + |v| a particle of this material can carry (CFL condition).
struct SignalSpeed {
  double J;
  double speed;
  double operator()(const WeaklyCompressibleFluid& f) const { return f.sound_speed(J) + speed; }
  double operator()(const ElasticSolid& s) const { return s.wave_speed(J) + speed; }
  double operator()(const RigidBody& r) const { return r.velocity.norm(); }
};

// Both components finite: Eigen's allFinite() compares x - x with itself, an out-of-line
// call per particle in the stress pass.
inline bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

std::string describe_material(const Body& b) {
  if (const auto* f = std::get_if<WeaklyCompressibleFluid>(&b.material)) {
    const std::string viscosity =
        f->viscosity > 0.0 ? format("viscosity %g Pa s", f->viscosity) : "inviscid (no viscous term)";
    const std::string cut_off =
        f->has_tension_cut_off()
            ? format(", tension cut-off p >= %g Pa (J held at %.6g)", f->min_pressure, f->largest_volume_ratio())
            : "";
    return format("fluid stress [%s]: %s EOS, K = %g Pa (c0 = %.3g m/s), rho0 = %g kg/m3, %s%s", b.name.c_str(),
                  f->eos == EquationOfState::kTait ? "Tait" : "linear", f->bulk_modulus, f->sound_speed(1.0),
                  f->density, viscosity.c_str(), cut_off.c_str());
  }
  if (const auto* e = std::get_if<ElasticSolid>(&b.material))
    return format("elastic stress [%s]: %s, E = %g Pa, nu = %g, rho0 = %g kg/m3", b.name.c_str(),
                  e->model == ElasticModel::kNeoHookean ? "Neo-Hookean" : "Saint Venant-Kirchhoff",
                  e->youngs_modulus, e->poisson_ratio, e->density);
  return "";  // rigid bodies carry no stress; the rigid motion effect describes them
}

}  // namespace

namespace {

// 1 / (sum_k N_i(x_k) dx), over an even lattice x_k = origin + (k + 1/2) dx covering the axis.
template <int P>
std::vector<double> lattice_fraction_inverse(const ClampedBSpline<P>& basis, double dx) {
  std::vector<double> sum(basis.basis_count(), 0.0);
  const int count = static_cast<int>(std::lround((basis.end() - basis.origin()) / dx));
  for (int k = 0; k < count; ++k) {
    typename ClampedBSpline<P>::Weights w, dw;
    const int first = basis.evaluate(basis.origin() + (k + 0.5) * dx, w, dw);
    for (int a = 0; a <= P; ++a) sum[first + a] += w[a] * dx;
  }
  for (double& v : sum) v = v > 0.0 ? 1.0 / v : 0.0;
  return sum;
}

}  // namespace

template <int P>
BsmpmSimulation<P>::BsmpmSimulation(StepState<P> state, SolverSettings settings,
                                    std::vector<std::unique_ptr<Effect<P>>> effects,
                                    std::vector<std::unique_ptr<Probe>> probes)
    : st_(std::move(state)), settings_(settings), effects_(std::move(effects)), probes_(std::move(probes)),
      j_min_(1.0 / settings.max_density_ratio), j_max_(1.0 / settings.min_density_ratio) {
  // The order of the effects' phases, not the order they were given in (EffectPhase).
  std::stable_sort(effects_.begin(), effects_.end(),
                   [](const auto& a, const auto& b) { return a->phase() < b->phase(); });
  for (auto& e : effects_) {
    if (e->hooks() & kHookGridForces) force_hooks_.push_back(e.get());
    if (e->hooks() & kHookConstrainVelocity) velocity_hooks_.push_back(e.get());
  }
  st_.schedules.resize(st_.bodies.size());
  if (settings_.fluid_volume == SolverSettings::FluidVolume::kProjected) {
    projection_ = DilatationProjection<P>(st_.grid);
    increment_scratch_.resize(st_.particles.size());
    gradient_scratch_.resize(st_.particles.size());
  }
  for (int i = 0; i < st_.grid.nx(); ++i) greville_x_.push_back(st_.grid.bx.greville(i));
  for (int j = 0; j < st_.grid.ny(); ++j) greville_y_.push_back(st_.grid.by.greville(j));
  // Half the interior D_p of APIC: h^2/4 for quadratic, h^2/3 for cubic B-splines.
  const double interior = P == 2 ? 0.25 : 1.0 / 3.0;
  affine_floor_ = 0.5 * interior * st_.grid.cell_size().cwiseProduct(st_.grid.cell_size());
  inverse_cell_ = st_.grid.cell_size().cwiseInverse();
  if (settings_.fluid_volume == SolverSettings::FluidVolume::kSmoothed) {
    smoothing_moments_.assign(kMoments * st_.grid.node_count(), 0.0);
    gradient_scratch_.resize(st_.particles.size());
  }
  st_.weights.resize(st_.particles.size());
  if (settings_.shifting > 0.0) {
    for (const Body& b : st_.bodies)
      if (is_fluid(b.material)) st_.layers[b.layer].tracks_volume = true;
    // The volume fraction an even lattice of particles (the seeding's) gives at each control
    // point is 1 inside but not next to a wall, where the clamped functions are lopsided:
    // phi is measured against it, so that the seeded state does not drift.
    Vec2 spacing = st_.grid.cell_size() / 2.0;
    for (const Body& b : st_.bodies)
      if (is_fluid(b.material)) { spacing = b.spacing; break; }
    inverse_integral_x_ = lattice_fraction_inverse(st_.grid.bx, spacing.x());
    inverse_integral_y_ = lattice_fraction_inverse(st_.grid.by, spacing.y());
  }
  for (auto& layer : st_.layers) layer.resize(st_.grid.node_count());
  st_.index_of_id.resize(st_.particles.size());
  for (std::size_t p = 0; p < st_.particles.size(); ++p) st_.index_of_id[st_.particles.id[p]] = p;
  // The cut-off scales with the lightest deformable particle: a rigid body's density is a
  // free parameter (it is infinitely heavy in the contact) and must not move the cut-off.
  double lightest = std::numeric_limits<double>::infinity(), lightest_rigid = lightest;
  for (const Body& b : st_.bodies) {
    double& bound = std::holds_alternative<RigidBody>(b.material) ? lightest_rigid : lightest;
    for (std::size_t p = b.begin; p < b.end; ++p) bound = std::min(bound, st_.particles.mass[p]);
  }
  st_.mass_cutoff = settings_.mass_cutoff_ratio * (std::isfinite(lightest) ? lightest : lightest_rigid);
  for (const Body& b : st_.bodies)
    for (std::size_t p = b.begin; p < b.end; ++p)
      max_signal_speed_ = std::max(
          max_signal_speed_, std::visit(SignalSpeed{st_.particles.J[p], st_.particles.v[p].norm()}, b.material));
  sort_particles_by_cell();
}

template <int P>
GridInfo BsmpmSimulation<P>::grid_info() const {
  return {P, st_.grid.origin(), st_.grid.cell_size(), st_.grid.bx.cells(), st_.grid.by.cells()};
}

template <int P>
MemoryUse BsmpmSimulation<P>::memory_use() const {
  MemoryUse m;
  m.particles = st_.particles.size();
  m.control_points = static_cast<std::size_t>(st_.grid.node_count());
  m.particle_bytes = st_.particles.bytes() + heap_bytes(st_.weights) + heap_bytes(st_.index_of_id) +
                     heap_bytes(gradient_scratch_) + heap_bytes(sort_key_) + heap_bytes(sort_order_) +
                     heap_bytes(column_scratch_) + heap_bytes(increment_scratch_) +
                     permute_scratch_.bytes();
  for (const StripSchedule& s : st_.schedules) m.particle_bytes += s.bytes();
  m.grid_bytes = heap_bytes(smoothing_moments_) + heap_bytes(sort_start_) + projection_.bytes();
  for (const GridLayer& layer : st_.layers) m.grid_bytes += layer.bytes();
  return m;
}

template <int P>
std::vector<std::string> BsmpmSimulation<P>::describe_effects() const {
  std::vector<std::string> lines;
  for (const Body& b : st_.bodies)
    if (std::string line = describe_material(b); !line.empty()) lines.push_back(line);
  for (const auto& e : effects_) lines.push_back(e->describe());
  for (const auto& p : probes_) lines.push_back("probe " + p->describe());
  return lines;
}

template <int P>
void BsmpmSimulation<P>::sample_probes() {
  if (probes_.empty()) return;
  const PhaseScope timed(st_.timer, StepPhase::kProbes);
  const ProbeContext ctx{st_.particles, st_.bodies, st_.index_of_id, st_.time, &st_.diagnostics.wall_impulse, st_.dt};
  for (auto& probe : probes_) probe->maybe_sample(ctx);
}

template <int P>
void BsmpmSimulation<P>::restore(Particles particles, const StepCounters& counters,
                                 const std::vector<ProbeState>& probes) {
  if (particles.size() != st_.particles.size() || probes.size() != probes_.size())
    throw std::invalid_argument("restore: the state is not of this scene");
  st_.particles = std::move(particles);
  for (std::size_t p = 0; p < st_.particles.size(); ++p) st_.index_of_id[st_.particles.id[p]] = p;
  st_.time = counters.time;
  st_.step = counters.step;
  max_signal_speed_ = counters.max_signal_speed;
  stats_ = counters.stats;
  for (std::size_t k = 0; k < probes.size(); ++k) probes_[k]->restore(probes[k]);
}

template <int P>
void BsmpmSimulation<P>::advance(double dt) {
  const PhaseScope timed(st_.timer, StepPhase::kOther);  // each phase times itself (phase_timer.hpp)
  st_.dt = dt;
  st_.diagnostics.reset();
  if (settings_.sort_interval > 0 && st_.step > 0 && st_.step % settings_.sort_interval == 0)
    sort_particles_by_cell();
  compute_weights();
  particle_to_grid();                       // eqs. 5-7
  for (auto* e : force_hooks_) {  // eq. 8
    const PhaseScope timed(st_.timer, StepPhase::kEffects);
    e->grid_forces(st_);
  }
  update_grid_velocity(dt);                 // eqs. 9-10 and the essential conditions
  stats_.work += st_.diagnostics.work;      // what the constraints did to the motion
  if (settings_.velocity_update == SolverSettings::VelocityUpdate::kApic) move_particles_and_remap_momentum<true>(dt);
  else move_particles_and_remap_momentum<false>(dt);  // eqs. 11-13
  update_remap_velocity();                  // eq. 13 and the essential conditions again
  const DeformationUpdate update = update_deformation_and_stress(dt);  // eq. 14 and the constitutive update
  max_signal_speed_ = update.max_signal_speed;  // bounds the next time step (CFL)
  clear_grid();
  st_.time += dt;
  ++st_.step;
  // After the counters: the state the error describes (and the run writes out) is this step's.
  if (update.invalid) throw_instability();
  sample_probes();
}

// Particles of each body sorted by cell (x-major, like the control points), so that the
// scatter and gather walk the grid in order. A counting sort: stable (the order a stable
// comparison sort gives), linear in the particles and cells, and into buffers kept from one
// sort to the next, so that it allocates nothing after the first.
template <int P>
void BsmpmSimulation<P>::sort_particles_by_cell() {
  const PhaseScope timed(st_.timer, StepPhase::kSort);
  auto& ps = st_.particles;
  const int cy = st_.grid.by.cells();
  const std::size_t cells = std::size_t(st_.grid.bx.cells()) * cy;
  for (const Body& b : st_.bodies) {
    const std::size_t n = b.size();
    sort_key_.resize(n);
    sort_order_.resize(n);
    sort_start_.assign(cells + 1, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& x = ps.x[b.begin + k];
      sort_key_[k] = std::uint32_t(st_.grid.bx.cell_of(x.x())) * cy + st_.grid.by.cell_of(x.y());
      ++sort_start_[sort_key_[k] + 1];
    }
    std::partial_sum(sort_start_.begin(), sort_start_.end(), sort_start_.begin());
    for (std::size_t k = 0; k < n; ++k) sort_order_[sort_start_[sort_key_[k]]++] = static_cast<std::uint32_t>(k);
    ps.permute(b.begin, sort_order_, permute_scratch_);
  }
  for (std::size_t p = 0; p < ps.size(); ++p) st_.index_of_id[ps.id[p]] = static_cast<std::uint32_t>(p);
}

// The basis at each particle, and per body its scatter schedule and the box of control
// points it touches. One parallel pass per body: the box as exact min/max reductions (the
// same for any thread count), the first columns copied into a compact array from which the
// serial schedule build reads 4 bytes a particle instead of striding through the weights.
template <int P>
void BsmpmSimulation<P>::compute_weights() {
  const PhaseScope timed(st_.timer, StepPhase::kWeights);
  auto& ps = st_.particles;
  column_scratch_.resize(ps.size());
  for (auto& layer : st_.layers) layer.active = NodeBox{};
  for (std::size_t b = 0; b < st_.bodies.size(); ++b) {
    const Body& body = st_.bodies[b];
    const long begin = static_cast<long>(body.begin), end = static_cast<long>(body.end);
    int i0 = st_.grid.nx(), i1 = 0, j0 = st_.grid.ny(), j1 = 0;
#pragma omp parallel for schedule(static) reduction(min : i0, j0) reduction(max : i1, j1)
    for (long p = begin; p < end; ++p) {
      auto& w = st_.weights[p];
      w.i0 = st_.grid.bx.evaluate(ps.x[p].x(), w.wx, w.gx);
      w.j0 = st_.grid.by.evaluate(ps.x[p].y(), w.wy, w.gy);
      column_scratch_[p] = w.i0;
      i0 = std::min(i0, w.i0);
      i1 = std::max(i1, w.i0);
      j0 = std::min(j0, w.j0);
      j1 = std::max(j1, w.j0);
    }
    st_.schedules[b].build(body.begin, body.end, st_.grid.nx(), [&](std::size_t p) { return column_scratch_[p]; });
    if (body.size() == 0) continue;
    st_.layers[body.layer].active.include(NodeBox{i0, i1 + P + 1, j0, j1 + P + 1});
  }
}

template <int P>
void BsmpmSimulation<P>::particle_to_grid() {
  const PhaseScope timed(st_.timer, StepPhase::kParticleToGrid);
  for (std::size_t b = 0; b < st_.bodies.size(); ++b) {
    // Mass gradients only for fields that take part in contact (their normals).
    const GridLayer& layer = st_.layers[st_.bodies[b].layer];
    const bool gradient = layer.tracks_mass_gradient, volume = layer.tracks_volume;
    const bool affine = settings_.velocity_update == SolverSettings::VelocityUpdate::kApic;
    if (volume) {
      if (affine) gradient ? scatter_body<true, true, true>(b) : scatter_body<false, true, true>(b);
      else gradient ? scatter_body<true, false, true>(b) : scatter_body<false, false, true>(b);
    } else {
      if (affine) gradient ? scatter_body<true, true, false>(b) : scatter_body<false, true, false>(b);
      else gradient ? scatter_body<true, false, false>(b) : scatter_body<false, false, false>(b);
    }
  }
}

template <int P>
template <bool kMassGradient, bool kAffine, bool kVolume>
void BsmpmSimulation<P>::scatter_body(std::size_t b) {
  const int ny = st_.grid.ny();
  auto& ps = st_.particles;
  GridLayer& layer = st_.layers[st_.bodies[b].layer];
  // Raw pointers, read once: Eigen's vector stores may alias anything, so through the
  // std::vectors every store would reload every array's address.
  double* const mass = layer.mass.data();
  Vec2* const momentum = layer.momentum.data();
  Vec2* const force = layer.force.data();
  Vec2* const mass_gradient = layer.mass_gradient.data();
  double* const volume = layer.volume.data();
  const double* const gx = greville_x_.data();
  const double* const gy = greville_y_.data();
  const ParticleWeights<P>* const weights = st_.weights.data();
  st_.schedules[b].for_each([&, mass, momentum, force, mass_gradient, volume, gx, gy, weights](std::uint32_t p) {
    const auto& w = weights[p];
    const double m = ps.mass[p];
    const Vec2 mv = m * ps.v[p];
    const double Vp = ps.volume(p);
    const Mat2 Vsigma = Vp * ps.stress[p];
    const Mat2 mC = m * ps.C[p];
    const Vec2 xp = ps.x[p];
    // S_Ip = N_a N_c and grad S_Ip = (N_a' N_c, N_a N_c'): the column's factors first.
    std::array<double, P + 1> dy;
    if constexpr (kAffine)
      for (int c = 0; c <= P; ++c) dy[c] = gy[w.j0 + c] - xp.y();
    for (int a = 0; a <= P; ++a) {
      const int row = (w.i0 + a) * ny + w.j0;
      const double wx = w.wx[a], mx = m * wx;
      // Vsigma grad S_Ip = N_c force_x + N_c' force_y
      const Vec2 force_x = w.gx[a] * Vsigma.col(0), force_y = wx * Vsigma.col(1);
      Vec2 at_column = mv;  // APIC: m (v_p + C_p (xi_I - x_p)) = at_column + dy mC.col(1)
      if constexpr (kAffine) at_column += (gx[w.i0 + a] - xp.x()) * mC.col(0);
      for (int c = 0; c <= P; ++c) {
        const double s = wx * w.wy[c];
        mass[row + c] += mx * w.wy[c];   // eq. 5
        if constexpr (kAffine) {
          momentum[row + c] += s * (at_column + dy[c] * mC.col(1));
        } else {
          momentum[row + c] += s * mv;   // eq. 6 (numerator)
        }
        force[row + c] -= w.wy[c] * force_x + w.gy[c] * force_y;  // eq. 7
        if constexpr (kMassGradient)  // contact normals
          mass_gradient[row + c] += m * Vec2(w.gx[a] * w.wy[c], wx * w.gy[c]);
        if constexpr (kVolume) volume[row + c] += s * Vp;
      }
    }
  });
}

template <int P>
void BsmpmSimulation<P>::constrain(VelocityPhase phase) {
  for (auto* e : velocity_hooks_) {
    const PhaseScope timed(st_.timer, st_.timer && e->phase() == EffectPhase::kContact ? StepPhase::kContact
                                                                                         : StepPhase::kEffects);
    e->constrain_velocity(st_, phase);
  }
}

template <int P>
void BsmpmSimulation<P>::update_grid_velocity(double dt) {
  const PhaseScope timed(st_.timer, StepPhase::kGridUpdate);
  const int ny = st_.grid.ny();
  const double cut = st_.mass_cutoff;
  for (auto& layer : st_.layers)
    for_each_node_parallel(layer.active, ny, [&](int n, int, int) {
      const double m = layer.mass[n];
      if (m > cut) {
        const Vec2 v = layer.momentum[n] / m;                     // v_I^k, eq. 6
        layer.velocity[n] = v + (dt / m) * layer.force[n];       // eqs. 9-10
      }
    });
  constrain(VelocityPhase::kUpdate);
  // The FLIP increment sees the constrained velocity: a_I = (v_I^{k+1} - v_I^k) / dt.
  for (auto& layer : st_.layers)
    for_each_node_parallel(layer.active, ny, [&](int n, int, int) {
      const double m = layer.mass[n];
      if (m > cut) layer.velocity_increment[n] = layer.velocity[n] - layer.momentum[n] / m;
      else layer.velocity[n].setZero();
    });
}

namespace {

// Puts a position that a step carried out of [lo, hi] back on its edge; true if it did.
inline bool keep_inside(Vec2& x, const Vec2& lo, const Vec2& hi) {
  const Vec2 inside = x.cwiseMax(lo).cwiseMin(hi);
  if (inside == x) return false;
  x = inside;
  return true;
}

// Adds S_Ip q to the particle's control points of `field`.
template <int P>
inline void scatter(const ParticleWeights<P>& w, const Vec2& q, Vec2* field, int ny) {
  for (int a = 0; a <= P; ++a) {
    const int row = (w.i0 + a) * ny + w.j0;
    for (int c = 0; c <= P; ++c) field[row + c] += (w.wx[a] * w.wy[c]) * q;
  }
}

// Adds S_Ip (m v_p + m C_p (xi_I - x_p)) to the particle's control points of `field`.
template <int P>
inline void scatter_affine(const ParticleWeights<P>& w, const Vec2& mv, const Mat2& mC, const Vec2& x,
                           const double* gx, const double* gy, Vec2* field, int ny) {
  for (int a = 0; a <= P; ++a) {
    const int row = (w.i0 + a) * ny + w.j0;
    const Vec2 at_column = mv + (gx[w.i0 + a] - x.x()) * mC.col(0);
    for (int c = 0; c <= P; ++c)
      field[row + c] += (w.wx[a] * w.wy[c]) * (at_column + (gy[w.j0 + c] - x.y()) * mC.col(1));
  }
}

// The grid velocity v_I^{k+1} and its increment at the particle (as gather_velocity()) and
// the APIC affine velocity C_p, in one walk over the particle's control points.
// C_p = B_p D_p^-1 (Jiang et al. 2015, eq. 10) about the control
// points' Greville abscissae, B_p = sum S_Ip v_I (xi_I - x_p)^T, D_p = sum S_Ip (xi_I - x_p)(xi_I - x_p)^T.
// B-splines reproduce linear functions with the Greville points (sum S_Ip xi_I = x_p), which
// is what makes the transfer exact for affine velocity fields and conserve momentum. Next
// to a wall the clamped basis makes D_p vanish like the distance to it; its diagonal is
// floored at half its interior value, so that a lone particle's own pressure cannot drive
// C_p faster than the time step resolves (a particle within ~h/8 of a wall loses part of
// its normal gradient). Linear splines have D_p = 0 at the nodes: there C_p is the gradient
// of the interpolated velocity, sum v_I grad S_Ip^T.
// With tensor-product weights S_Ip = N_a(x) N_c(y), sum_c N_c = 1 and linear reproduction,
// D_p is diagonal, D_xx = sum_a N_a (xi_a - x)^2 and D_yy = sum_c N_c (eta_c - y)^2: it is
// evaluated per axis, and B_p through the row sums of the velocities.
template <int P>
inline Mat2 gather_velocity_and_affine(const ParticleWeights<P>& w, const GridLayer& layer, int ny, const Vec2& x,
                                       const std::vector<double>& gx, const std::vector<double>& gy,
                                       const Vec2& floor, GridVelocityAt& g) {
  if constexpr (P == 1) {
    g = gather_velocity<P>(w, layer, ny);
    Mat2 B = Mat2::Zero();
    for (int a = 0; a <= P; ++a) {
      const int row = (w.i0 + a) * ny + w.j0;
      for (int c = 0; c <= P; ++c)
        B += layer.velocity[row + c] * Vec2(w.gx[a] * w.wy[c], w.wx[a] * w.gy[c]).transpose();
    }
    return B;
  } else {
    // Per column a, the sums over c, then over a: S_Ip = N_a N_c factors every sum.
    std::array<double, P + 1> wdy;
    double Dyy = 0.0, Dxx = 0.0;
    for (int c = 0; c <= P; ++c) {
      const double dy = gy[w.j0 + c] - x.y();
      wdy[c] = w.wy[c] * dy;
      Dyy += wdy[c] * dy;
    }
    Vec2 velocity = Vec2::Zero(), increment = Vec2::Zero(), col0 = Vec2::Zero(), col1 = Vec2::Zero();
    const Vec2* const v = layer.velocity.data();
    const Vec2* const dv = layer.velocity_increment.data();
    for (int a = 0; a <= P; ++a) {
      const int row = (w.i0 + a) * ny + w.j0;
      const double dx = gx[w.i0 + a] - x.x();
      Dxx += w.wx[a] * dx * dx;
      // sum_c N_c v, sum_c N_c dv, sum_c N_c dy v
      Vec2 along = Vec2::Zero(), along_increment = Vec2::Zero(), across = Vec2::Zero();
      for (int c = 0; c <= P; ++c) {
        along += w.wy[c] * v[row + c];
        along_increment += w.wy[c] * dv[row + c];
        across += wdy[c] * v[row + c];
      }
      velocity += w.wx[a] * along;
      increment += w.wx[a] * along_increment;
      col0 += (w.wx[a] * dx) * along;
      col1 += w.wx[a] * across;
    }
    g.velocity = velocity;
    g.increment = increment;
    Mat2 B;
    B.col(0) = col0 / std::max(Dxx, floor.x());
    B.col(1) = col1 / std::max(Dyy, floor.y());
    return B;
  }
}

// Particle shifting (after Lind et al. 2012, J. Comput. Phys. 231:1499, carried to the grid):
// phi_I = sum_p S_Ip V_p / integral(N_I) is the volume fraction at the control point (1 where
// particles fill the support evenly); a fluid particle inside the water (phi >= 0.95 at it)
// drifts by -D grad phi, towards where particles are too sparse. Near a free surface or a
// solid phi drops below the threshold and nothing moves, so the surface is not smeared out.
template <int P>
inline Vec2 shift_of(const ParticleWeights<P>& w, const std::vector<double>& volume, int ny,
                     const std::vector<double>& inv_ix, const std::vector<double>& inv_iy, double D) {
  // phi_I = V_I / (int N_i int N_j) factors per axis: the sums over c first, then over a.
  std::array<double, P + 1> wy, gy;
  for (int c = 0; c <= P; ++c) {
    wy[c] = w.wy[c] * inv_iy[w.j0 + c];
    gy[c] = w.gy[c] * inv_iy[w.j0 + c];
  }
  double phi = 0.0;
  Vec2 grad = Vec2::Zero();
  for (int a = 0; a <= P; ++a) {
    const double* const V = volume.data() + (w.i0 + a) * ny + w.j0;
    double along = 0.0, across = 0.0;  // sum_c N_c V / int N_j, sum_c N_c' V / int N_j
    for (int c = 0; c <= P; ++c) {
      along += wy[c] * V[c];
      across += gy[c] * V[c];
    }
    const double ix = inv_ix[w.i0 + a];
    phi += w.wx[a] * ix * along;
    grad += ix * Vec2(w.gx[a] * along, w.wx[a] * across);
  }
  if (phi < 0.95) return Vec2::Zero();
  return -D * grad;
}

}  // namespace

// G2P and the remap in one pass over the particles: the new velocity (eq. 11) and position
// (eq. 12) from the grid, positions a step would carry out of the domain put back inside it
// (counted in stats().clamped_positions), and the new momentum scattered back to the grid
// (eq. 13; update_remap_velocity() divides it by the nodal mass).
template <int P>
template <bool kAffine>
void BsmpmSimulation<P>::move_particles_and_remap_momentum(double dt) {
  const PhaseScope timed(st_.timer, StepPhase::kGridToParticle);
  const int ny = st_.grid.ny();
  auto& ps = st_.particles;
  const double flip = settings_.flip_fraction;
  const double h_min = st_.grid.cell_size().minCoeff();
  const double shift_scale = settings_.shifting * h_min * h_min;
  const Vec2 margin = 1e-9 * st_.grid.cell_size();
  const Vec2 lo = st_.grid.origin() + margin, hi = st_.grid.extent_max() - margin;
  long clamped = 0;
  for (std::size_t b = 0; b < st_.bodies.size(); ++b) {
    const Body& body = st_.bodies[b];
    GridLayer& layer = st_.layers[body.layer];
    const RigidBody* rigid = std::get_if<RigidBody>(&body.material);
    const bool shift = layer.tracks_volume && is_fluid(body.material);
    Vec2* const remap = layer.remap_velocity.data();  // read once (see scatter_body)
    long body_clamped = 0;
    st_.schedules[b].for_each([&, remap](std::uint32_t p) {
      const auto& w = st_.weights[p];
      GridVelocityAt grid;
      Mat2 C = Mat2::Zero();
      if (kAffine && !rigid)
        C = gather_velocity_and_affine<P>(w, layer, ny, ps.x[p], greville_x_, greville_y_, affine_floor_, grid);
      else grid = gather_velocity<P>(w, layer, ny);
      Vec2 v, v_new = grid.velocity;
      if (rigid) {
        v = rigid->velocity;
        v_new = v;
      } else {
        v = flip * (ps.v[p] + grid.increment) + (1.0 - flip) * v_new;  // eq. 11 (flip = 1: paper)
      }
      const Vec2 x_old = ps.x[p];
      Vec2 x = ps.x[p] + dt * v_new;                                   // eq. 12 with v_I^{k+1}
      if (shift) {
        Vec2 dx = shift_of<P>(w, layer.volume, ny, inverse_integral_x_, inverse_integral_y_, shift_scale);
        // A shift never carries a particle out of the domain: that part of it is dropped.
        for (int k = 0; k < 2; ++k)
          if (x[k] + dx[k] < lo[k] || x[k] + dx[k] > hi[k]) dx[k] = 0.0;
        x += dx;
        if constexpr (kAffine) v += C * dx;
      }
      ps.v[p] = v;
      if (keep_inside(x, lo, hi)) {
#pragma omp atomic
        ++body_clamped;
      }
      ps.x[p] = x;
      if constexpr (kAffine) {
        ps.C[p] = C;
        scatter_affine<P>(w, ps.mass[p] * v, ps.mass[p] * C, x_old, greville_x_.data(), greville_y_.data(),
                          remap, ny);  // eq. 13 with the affine field
      } else {
        scatter<P>(w, ps.mass[p] * v, remap, ny);      // eq. 13
      }
    });
    clamped += body_clamped;
  }
  stats_.clamped_positions += clamped;
}

// The remapped velocity v_bar_I = sum_p S_Ip m_p v_p / m_I (eq. 13), then the essential
// conditions again: the strain increment (eq. 14) is taken from it.
template <int P>
void BsmpmSimulation<P>::update_remap_velocity() {
  const PhaseScope timed(st_.timer, StepPhase::kGridUpdate);
  const int ny = st_.grid.ny();
  const double cut = st_.mass_cutoff;
  for (auto& layer : st_.layers)
    for_each_node_parallel(layer.active, ny, [&](int n, int, int) {
      const double m = layer.mass[n];
      if (m > cut) layer.remap_velocity[n] /= m;  // eq. 13
      else layer.remap_velocity[n].setZero();
    });
  constrain(VelocityPhase::kRemap);
}

// Per body, visiting its material once: the deformation from the remapped velocities
// (eq. 14), then the stress. The fastest signal bounds the next time step; a particle whose
// state turned non-finite or left the density range makes the step invalid.
template <int P>
typename BsmpmSimulation<P>::DeformationUpdate BsmpmSimulation<P>::update_deformation_and_stress(double dt) {
  const PhaseScope timed(st_.timer, StepPhase::kStress);
  DeformationUpdate all;
  for (std::size_t b = 0; b < st_.bodies.size(); ++b) {
    const Body& body = st_.bodies[b];
    const BodyParticles particles{b, static_cast<long>(body.begin), static_cast<long>(body.end),
                                  st_.layers[body.layer].remap_velocity};
    const DeformationUpdate update =
        std::visit([&](const auto& material) { return update_body(particles, material, dt); }, body.material);
    all.max_signal_speed = std::max(all.max_signal_speed, update.max_signal_speed);
    all.invalid = all.invalid || update.invalid;
  }
  return all;
}

// Fluid: J <- J det(I + dt L), optionally smoothed through the grid, then the pressure of
// the equation of state and the viscous stress (compiled out when mu = 0).
template <int P>
typename BsmpmSimulation<P>::DeformationUpdate BsmpmSimulation<P>::update_body(const BodyParticles& body,
                                                                               const WeaklyCompressibleFluid& mat,
                                                                               double dt) {
  const int ny = st_.grid.ny();
  auto& ps = st_.particles;
  double body_speed = 0.0;
  bool body_invalid = false;
  const bool smooth = settings_.fluid_volume != SolverSettings::FluidVolume::kParticle;
  const bool fitted = settings_.fluid_volume == SolverSettings::FluidVolume::kSmoothed;
  if (settings_.fluid_volume == SolverSettings::FluidVolume::kProjected) {
    // The volumetric increment of each particle, projected onto the lower splines (F-bar).
#pragma omp parallel for schedule(static)
    for (long p = body.begin; p < body.end; ++p) {
      const Mat2 L = velocity_gradient<P>(st_.weights[p], body.velocity, ny);
      gradient_scratch_[p] = L;
      increment_scratch_[p] = (Mat2::Identity() + dt * L).determinant() - 1.0;
    }
    {
      const PhaseScope timed(st_.timer, StepPhase::kSmoothing);
      projection_.project(st_, st_.schedules[body.index], body.begin, body.end, increment_scratch_);
    }
#pragma omp parallel for schedule(static)
    for (long p = body.begin; p < body.end; ++p) ps.J[p] *= 1.0 + increment_scratch_[p];
  } else if (fitted) {
    // One pass in the scatter's order: the velocity gradient, the volume change (eq. 14) and
    // the particle's share of the least-squares moments; then the fit at the control points.
    // The pass below reads the fitted J back before it enters the equation of state.
    const PhaseScope timed(st_.timer, StepPhase::kSmoothing);
    st_.schedules[body.index].for_each([&](std::uint32_t p) {
      const Mat2 L = velocity_gradient<P>(st_.weights[p], body.velocity, ny);
      gradient_scratch_[p] = L;
      ps.J[p] *= (Mat2::Identity() + dt * L).determinant();
      add_volume_moments(p);
    });
    fit_volume_ratio(body.index);
  }
  // With a tension cut-off, water does not stretch past the J at which it reaches it
  // (method.md §4): a particle there keeps its volume, as water in a thinning sheet does.
  const double j_cut = mat.largest_volume_ratio();
  auto run = [&](auto viscous) {
#pragma omp parallel for schedule(static) reduction(max : body_speed) reduction(|| : body_invalid)
    for (long p = body.begin; p < body.end; ++p) {
      Mat2 L;
      double J;
      if (smooth) {
        L = gradient_scratch_[p];
        J = fitted ? fitted_volume_ratio(p) : ps.J[p];
        ps.J[p] = J;
      } else {
        L = velocity_gradient<P>(st_.weights[p], body.velocity, ny);
        J = ps.J[p] * (Mat2::Identity() + dt * L).determinant();
        ps.J[p] = J;
      }
      if (J > j_cut) ps.J[p] = J = j_cut;
      const double pressure = mat.pressure(J);
      ps.pressure[p] = pressure;
      ps.stress[p] = mat.template stress<decltype(viscous)::value>(pressure, L);
      body_speed = std::max(body_speed, SignalSpeed{J, ps.v[p].norm()}(mat));
      body_invalid = body_invalid || !density_in_range(J) || !std::isfinite(pressure) || !finite(ps.v[p]) ||
                     !finite(ps.x[p]);
    }
  };
  // Viscosity only when mu > 0: the inviscid loop has no deviatoric term at all.
  if (mat.viscosity > 0.0) run(std::true_type{});
  else run(std::false_type{});
  if (fitted) clear_volume_moments(body.index);
  return {body_speed, body_invalid};
}

// Elastic solid: F <- (I + dt L) F, J = det F, then the hyperelastic Cauchy stress.
template <int P>
typename BsmpmSimulation<P>::DeformationUpdate BsmpmSimulation<P>::update_body(const BodyParticles& body,
                                                                               const ElasticSolid& mat, double dt) {
  const int ny = st_.grid.ny();
  auto& ps = st_.particles;
  double body_speed = 0.0;
  bool body_invalid = false;
#pragma omp parallel for schedule(static) reduction(max : body_speed) reduction(|| : body_invalid)
  for (long p = body.begin; p < body.end; ++p) {
    const Mat2 L = velocity_gradient<P>(st_.weights[p], body.velocity, ny);
    const Mat2 F = (Mat2::Identity() + dt * L) * ps.F[p];
    const double J = F.determinant();
    ps.F[p] = F;
    ps.J[p] = J;
    const Mat2 sigma = mat.stress(F);
    ps.stress[p] = sigma;
    ps.pressure[p] = -0.5 * sigma.trace();
    body_speed = std::max(body_speed, SignalSpeed{J, ps.v[p].norm()}(mat));
    body_invalid = body_invalid || !density_in_range(J) || !sigma.allFinite() || !finite(ps.v[p]) ||
                   !finite(ps.x[p]);
  }
  return {body_speed, body_invalid};
}

// Rigid body: no deformation, no stress; its prescribed speed still bounds the time step.
template <int P>
typename BsmpmSimulation<P>::DeformationUpdate BsmpmSimulation<P>::update_body(const BodyParticles&,
                                                                               const RigidBody& mat, double) {
  return {SignalSpeed{1.0, 0.0}(mat), false};
}

// Names the first invalid particle and the field that is wrong (a NumericalError the run
// reports and stops on; the field names are those of io/particle_fields).
template <int P>
void BsmpmSimulation<P>::throw_instability() const {
  const auto& ps = st_.particles;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const Body& body = st_.bodies[ps.body[p]];
    if (std::holds_alternative<RigidBody>(body.material)) continue;
    std::string field;
    if (!ps.x[p].allFinite()) field = "position is not finite";
    else if (!ps.v[p].allFinite()) field = "velocity is not finite";
    else if (!std::isfinite(ps.pressure[p])) field = "pressure is not finite";
    else if (!ps.stress[p].allFinite()) field = "stress_tensor is not finite";
    else if (!std::isfinite(ps.J[p])) field = "volume_ratio is not finite";
    else if (!density_in_range(ps.J[p]))
      field = format("density %.4g rho0 (volume_ratio J = %.4g) is outside the range [%g, %g] rho0 (solver.density_range)",
                     1.0 / ps.J[p], ps.J[p], settings_.min_density_ratio, settings_.max_density_ratio);
    else continue;
    throw NumericalError(format(
        "numerical instability at step %ld (t = %.6g s): body '%s', particle %u at (%.4g, %.4g): %s "
        "(|v| = %.3g m/s, p = %.3g Pa); reduce the time step (time.cfl or time.dt)",
        st_.step, st_.time, body.name.c_str(), ps.id[p], ps.x[p].x(), ps.x[p].y(), field.c_str(), ps.v[p].norm(),
        ps.pressure[p]));
  }
  throw NumericalError(format("numerical instability at step %ld (t = %.6g s): a non-finite state; reduce the time "
                              "step (time.cfl or time.dt)", st_.step, st_.time));
}

// Smoothing of the fluid's volume ratio through the grid (solver.fluid_volume = "smoothed"),
// in the velocity-gradient pass of update_body (moments), fit_volume_ratio and the stress pass:
// at each control point a mass-weighted least-squares linear fit of the particles' J around
// its Greville point, J ~ J_I + g_I . (x - xi_I), then J_p = sum_I S_Ip (J_I + g_I . (x_p - xi_I)).
// It removes the particle-to-particle pressure noise of weakly compressible MPM. A plain
// mass average (Shepard) would take the value of the particles' centroid for the control
// point's, which next to a wall or a free surface lies a fraction of a cell inside: the
// fit reproduces linear J fields exactly, walls included. Where the particles around a
// control point do not span a plane (a thin film), the fit falls back to the mass average.
// The offsets x_p - xi_I use the particles' new positions x^{k+1}, where their J now sits;
// the step's weights S_Ip(x^k) only localise the fit, which stays exact for linear fields.
//
// Moments per control point, with d = (x_p - xi_I) / h:
// sum m S, sum m S d (2), sum m S d d^T (3), sum m S J, sum m S J d (2).
// S_Ip = N_a(x) N_c(y) and d = (dx_a, dy_c): every moment is a product of one factor per
// axis, N_a {1, dx_a, dx_a^2} times N_c {1, dy_c, dy_c^2}, formed once per particle.
template <int P>
void BsmpmSimulation<P>::add_volume_moments(std::uint32_t p) {
  double* const moments = smoothing_moments_.data();
  const int ny = st_.grid.ny();
  const Vec2& x = st_.particles.x[p];
  const auto& w = st_.weights[p];
  const double m = st_.particles.mass[p], mJ = m * st_.particles.J[p];
  std::array<double, P + 1> y0, y1, y2;  // N_c {1, dy, dy^2}
  for (int c = 0; c <= P; ++c) {
    const double dy = (x.y() - greville_y_[w.j0 + c]) * inverse_cell_.y();
    y0[c] = w.wy[c];
    y1[c] = w.wy[c] * dy;
    y2[c] = y1[c] * dy;
  }
  for (int a = 0; a <= P; ++a) {
    const double dx = (x.x() - greville_x_[w.i0 + a]) * inverse_cell_.x();
    const double x0 = m * w.wx[a], x1 = x0 * dx, x2 = x1 * dx;
    const double j0 = mJ * w.wx[a], j1 = j0 * dx;
    double* mom = moments + kMoments * ((w.i0 + a) * ny + w.j0);
    for (int c = 0; c <= P; ++c, mom += kMoments) {
      mom[0] += x0 * y0[c];
      mom[1] += x1 * y0[c];
      mom[2] += x0 * y1[c];
      mom[3] += x2 * y0[c];
      mom[4] += x1 * y1[c];
      mom[5] += x0 * y2[c];
      mom[6] += j0 * y0[c];
      mom[7] += j1 * y0[c];
      mom[8] += j0 * y1[c];
    }
  }
}

// Each control point's normal equations A (J_I, g_I h) = r, solved by cofactors; the fit
// replaces the first three moments.
template <int P>
void BsmpmSimulation<P>::fit_volume_ratio(std::size_t body_index) {
  const int ny = st_.grid.ny();
  const NodeBox b = st_.layers[st_.bodies[body_index].layer].active;
#pragma omp parallel for schedule(static)
  for (int i = b.i0; i < b.i1; ++i)
    for (int j = b.j0; j < b.j1; ++j) {
      double* mom = &smoothing_moments_[kMoments * (i * ny + j)];
      const double a00 = mom[0];
      if (a00 <= 0.0) continue;
      const double a01 = mom[1], a02 = mom[2], a11 = mom[3], a12 = mom[4], a22 = mom[5];
      const double r0 = mom[6], r1 = mom[7], r2 = mom[8];
      // Spread of the particles about their centroid (in cells^2): a thin film cannot
      // carry a gradient across itself.
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
}

// J_p = sum_I S_Ip (J_I + g_I . (x_p - xi_I)) from the fitted control points.
template <int P>
double BsmpmSimulation<P>::fitted_volume_ratio(std::size_t p) const {
  const int ny = st_.grid.ny();
  const Vec2& x = st_.particles.x[p];
  const auto& w = st_.weights[p];
  std::array<double, P + 1> dy;
  for (int c = 0; c <= P; ++c) dy[c] = (x.y() - greville_y_[w.j0 + c]) * inverse_cell_.y();
  double J = 0.0;
  for (int a = 0; a <= P; ++a) {
    const double dx = (x.x() - greville_x_[w.i0 + a]) * inverse_cell_.x();
    const double* fit = &smoothing_moments_[kMoments * ((w.i0 + a) * ny + w.j0)];
    double row = 0.0;
    for (int c = 0; c <= P; ++c, fit += kMoments) row += w.wy[c] * (fit[0] + fit[1] * dx + fit[2] * dy[c]);
    J += w.wx[a] * row;
  }
  return J;
}

template <int P>
void BsmpmSimulation<P>::clear_volume_moments(std::size_t body_index) {
  const int ny = st_.grid.ny();
  const NodeBox b = st_.layers[st_.bodies[body_index].layer].active;
#pragma omp parallel for schedule(static) if ((b.i1 - b.i0) * (b.j1 - b.j0) > 4096)
  for (int i = b.i0; i < b.i1; ++i)
    std::fill_n(smoothing_moments_.begin() + kMoments * (i * ny + b.j0), kMoments * (b.j1 - b.j0), 0.0);
}

template <int P>
void BsmpmSimulation<P>::clear_grid() {
  const PhaseScope timed(st_.timer, StepPhase::kClearGrid);
  const int ny = st_.grid.ny();
  for (auto& layer : st_.layers) {
    const NodeBox& b = layer.active;
#pragma omp parallel for schedule(static) if ((b.i1 - b.i0) * (b.j1 - b.j0) > 4096)
    for (int i = b.i0; i < b.i1; ++i) {
      const int first = i * ny + b.j0, count = b.j1 - b.j0;
      std::fill_n(layer.mass.begin() + first, count, 0.0);
      std::fill_n(layer.momentum.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.force.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.velocity.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.velocity_increment.begin() + first, count, Vec2::Zero());
      std::fill_n(layer.remap_velocity.begin() + first, count, Vec2::Zero());
      if (layer.tracks_mass_gradient) std::fill_n(layer.mass_gradient.begin() + first, count, Vec2::Zero());
      if (layer.tracks_volume) std::fill_n(layer.volume.begin() + first, count, 0.0);
    }
  }
}

template class BsmpmSimulation<1>;
template class BsmpmSimulation<2>;
template class BsmpmSimulation<3>;

}  // namespace bsmpm

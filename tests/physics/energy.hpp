// Momentum and energy of a simulation's particles, for the bookkeeping checks of the
// physics tests.
#pragma once

#include <cmath>

#include "step/simulation.hpp"

namespace bsmpm::test {

inline Vec2 momentum(const Simulation& sim) {
  const Particles& ps = sim.particles();
  Vec2 m = Vec2::Zero();
  for (std::size_t p = 0; p < ps.size(); ++p) m += ps.mass[p] * ps.v[p];
  return m;
}

inline double kinetic_energy(const Simulation& sim) {
  const Particles& ps = sim.particles();
  double e = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) e += 0.5 * ps.mass[p] * ps.v[p].squaredNorm();
  return e;
}

// Potential energy in uniform gravity g (a vector), relative to the origin.
inline double potential_energy(const Simulation& sim, const Vec2& g) {
  const Particles& ps = sim.particles();
  double e = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) e -= ps.mass[p] * g.dot(ps.x[p]);
  return e;
}

// Stored energy per unit reference volume, for each constitutive model (plane strain).
struct StoredEnergy {
  const Particles& ps;
  std::size_t p;
  // Compressible Neo-Hookean, whose stress is mu/J (F F^T - I) + lambda ln(J)/J I:
  // W = mu/2 (tr(F^T F) - 2) - mu ln J + lambda/2 (ln J)^2. Saint Venant-Kirchhoff:
  // W = lambda/2 tr(E)^2 + mu E:E.
  double operator()(const ElasticSolid& e) const {
    const Mat2& F = ps.F[p];
    const double lambda = e.lame_lambda(), mu = e.shear_modulus();
    if (e.model == ElasticModel::kNeoHookean) {
      const double lnJ = std::log(F.determinant());
      return 0.5 * mu * ((F.transpose() * F).trace() - 2.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
    }
    const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
    return 0.5 * lambda * E.trace() * E.trace() + mu * (E.array() * E.array()).sum();
  }
  // Fluid: the work of compression, W(J) = -int_1^J p(J') dJ' (Simpson's rule; p is smooth).
  double operator()(const WeaklyCompressibleFluid& f) const {
    const double J = ps.J[p];
    const int n = 16;
    const double step = (J - 1.0) / n;
    double sum = f.pressure(1.0) + f.pressure(J);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * f.pressure(1.0 + k * step);
    return -sum * step / 3.0;
  }
  double operator()(const RigidBody&) const { return 0.0; }
  double operator()(const IncompressibleFluid&) const { return 0.0; }  // no compression, no stored energy
};

inline double stored_energy(const Simulation& sim) {
  const Particles& ps = sim.particles();
  double e = 0.0;
  for (const Body& b : sim.bodies())
    for (std::size_t p = b.begin; p < b.end; ++p) e += ps.volume0[p] * std::visit(StoredEnergy{ps, p}, b.material);
  return e;
}

}  // namespace bsmpm::test

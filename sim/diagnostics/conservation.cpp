#include "diagnostics/conservation.hpp"

namespace bsmpm {

ConservationTotals measure_conservation(const Simulation& sim, const Vec2& gravity) {
  ConservationTotals c;
  c.time = sim.time();
  c.step = sim.step_count();
  c.work = sim.stats().work;
  const Particles& ps = sim.particles();
  for (const Body& body : sim.bodies()) {
    if (is_rigid(body.material)) continue;
    // Stored energy per unit reference volume of one particle (docs/method.md §4, §5).
    auto stored_energy = [&](std::size_t p) {
      return std::visit([&](const auto& m) { return m.stored_energy(ps.F[p], ps.J[p]); }, body.material);
    };
    for (std::size_t p = body.begin; p < body.end; ++p) {
      const double m = ps.mass[p];
      c.mass += m;
      c.momentum += m * ps.v[p];
      c.kinetic += 0.5 * m * ps.v[p].squaredNorm();
      c.gravitational -= m * gravity.dot(ps.x[p]);
      c.work_gravity += m * gravity.dot(ps.x[p] - ps.x0[p]);
      c.elastic += ps.volume0[p] * stored_energy(p);
    }
  }
  return c;
}

const std::vector<std::string>& conservation_columns() {
  static const std::vector<std::string> columns = {
      "t",       "step",          "mass",  "momentum_x",   "momentum_y", "kinetic",      "gravitational",
      "elastic", "total",         "work_gravity", "work_walls", "work_clamps", "work_contact",
      "work_rigid_contact"};
  return columns;
}

const std::vector<std::string>& conservation_units() {
  static const std::vector<std::string> units = {"s",   "1",   "kg/m", "kg/s", "kg/s", "J/m", "J/m",
                                                 "J/m", "J/m", "J/m",  "J/m",  "J/m",  "J/m", "J/m"};
  return units;
}

std::vector<double> conservation_row(const ConservationTotals& c) {
  return {c.time,    static_cast<double>(c.step),
          c.mass,    c.momentum.x(),
          c.momentum.y(), c.kinetic,
          c.gravitational, c.elastic,
          c.total(), c.work_gravity,
          c.work.walls, c.work.clamps,
          c.work.contact, c.work.rigid_contact};
}

}  // namespace bsmpm

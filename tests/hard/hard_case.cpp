#include "hard_case.hpp"

#include <cmath>
#include <limits>

#include "core/format.hpp"
#include "diagnostics/conservation.hpp"
#include "scene/run_cost.hpp"
#include "step/effects/gravity.hpp"

namespace bsmpm::test {

namespace {

// How deep a point lies inside a rectangle (> 0 inside), in metres.
double depth_in(const Rectangle& r, const Vec2& x) {
  return std::min({x.x() - r.min.x(), r.max.x() - x.x(), x.y() - r.min.y(), r.max.y() - x.y()});
}

// The deepest fluid particle inside any solid body. A rigid body is its shape moved by its
// velocity; an elastic body is its shape in the reference configuration, into which a fluid
// particle is mapped through the nearest particle of the solid, X = X_s + F_s^-1 (x - x_s).
double deepest_penetration(const Simulation& sim, const SceneDescription& scene) {
  const Particles& ps = sim.particles();
  const auto& bodies = sim.bodies();
  double deepest = 0.0;
  for (std::size_t s = 0; s < bodies.size(); ++s) {
    const Body& solid = bodies[s];
    if (is_fluid(solid.material)) continue;
    const auto* shape = std::get_if<Rectangle>(&scene.bodies[s].shape);
    if (!shape) continue;
    Rectangle now{Vec2::Constant(1e300), Vec2::Constant(-1e300)};  // where the solid is
    for (std::size_t p = solid.begin; p < solid.end; ++p) {
      now.min = now.min.cwiseMin(ps.x[p] - solid.spacing);
      now.max = now.max.cwiseMax(ps.x[p] + solid.spacing);
    }
    const bool rigid = is_rigid(solid.material);
    const Vec2 moved = rigid ? Vec2(std::get<RigidBody>(solid.material).velocity * sim.time()) : Vec2::Zero();
    const Rectangle rigid_now{shape->min + moved, shape->max + moved};
    for (const Body& fluid : bodies) {
      if (!is_fluid(fluid.material)) continue;
      for (std::size_t p = fluid.begin; p < fluid.end; ++p) {
        const Vec2& x = ps.x[p];
        if (depth_in(now, x) <= 0.0) continue;
        double depth;
        if (rigid) {
          depth = depth_in(rigid_now, x);
        } else {
          std::size_t nearest = solid.begin;
          double best = std::numeric_limits<double>::infinity();
          for (std::size_t q = solid.begin; q < solid.end; ++q)
            if (const double d = (ps.x[q] - x).squaredNorm(); d < best) best = d, nearest = q;
          const Vec2 X = ps.x0[nearest] + ps.F[nearest].inverse() * (x - ps.x[nearest]);
          depth = depth_in(*shape, X);
        }
        deepest = std::max(deepest, depth);
      }
    }
  }
  return deepest;
}

}  // namespace

HardCaseReport run_hard_case(const std::string& name, const std::vector<std::string>& overrides,
                             double fixed_dt_factor) {
  HardCaseReport r;
  SceneDescription scene = load_scene(source_path("tests/hard/scenes/" + name), overrides);
  if (fixed_dt_factor > 0.0) {
    scene.time.mode = TimeStepSettings::Mode::kFixed;
    scene.time.dt = fixed_dt_factor * predict_run_cost(scene).stable_dt;
  }
  auto sim = build_simulation(scene);
  const Particles& ps = sim->particles();
  const GridInfo g = sim->grid_info();
  r.cell = std::min(g.cell_size.x(), g.cell_size.y());
  r.end_time = scene.time.end;
  r.particles = static_cast<long>(ps.size());
  const auto* gravity = scene.effect_parameters<GravityParameters>();
  const Vec2 gvec = gravity ? gravity->vector() : Vec2::Zero();
  const Vec2 lo = g.origin, hi = g.extent_max();

  auto mass_in_id_order = [&] {
    double m = 0.0;
    for (std::size_t id = 0; id < ps.size(); ++id) m += ps.mass[sim->index_of_id()[id]];
    return m;
  };
  const double mass0 = mass_in_id_order();
  const ConservationTotals start = measure_conservation(*sim, gvec);
  double above_floor = 0.0;
  for (const Body& b : sim->bodies())
    if (!is_rigid(b.material))
      for (std::size_t p = b.begin; p < b.end; ++p) above_floor += ps.mass[p] * gvec.norm() * (ps.x[p].y() - lo.y());
  r.energy_scale = above_floor + start.kinetic;

  auto check = [&] {
    const ConservationTotals now = measure_conservation(*sim, gvec);
    r.energy_scale = std::max(r.energy_scale, now.work.rigid_contact);
    const double excess = now.total() - start.total() - now.work.external();
    if (sim->step_count() > 0) r.max_energy_excess = std::max(r.max_energy_excess, excess);
    r.final_energy_change = now.total() - start.total();
    r.mass_exact = r.mass_exact && mass_in_id_order() == mass0;
    for (const Body& b : sim->bodies())
      for (std::size_t p = b.begin; p < b.end; ++p) {
        const bool finite = ps.x[p].allFinite() && ps.v[p].allFinite() && std::isfinite(ps.J[p]) &&
                            std::isfinite(ps.pressure[p]) && ps.stress[p].allFinite() && ps.F[p].allFinite();
        r.finite = r.finite && finite;
        r.inside_tank = r.inside_tank && (ps.x[p].array() >= lo.array()).all() && (ps.x[p].array() <= hi.array()).all();
        if (!is_fluid(b.material)) continue;
        r.min_density = std::min(r.min_density, 1.0 / ps.J[p]);
        r.max_density = std::max(r.max_density, 1.0 / ps.J[p]);
        r.max_speed = std::max(r.max_speed, ps.v[p].norm());
        r.max_displacement = std::max(r.max_displacement, (ps.x[p] - ps.x0[p]).norm());
      }
    r.max_penetration = std::max(r.max_penetration, deepest_penetration(*sim, scene) / r.cell);
  };
  check();
  const double h_min = r.cell;
  try {
    while (sim->time() < scene.time.end * (1.0 - 1e-12)) {
      const double dt = std::min(time_step(scene.time, sim->max_signal_speed(), h_min), scene.time.end - sim->time());
      sim->advance(dt);
      r.dt_min = std::min(r.dt_min, dt);
      r.dt_max = std::max(r.dt_max, dt);
      ++r.steps;
      check();
    }
    r.finished = true;
  } catch (const NumericalError& e) {
    r.error = e.what();
    check();
  }
  r.max_energy_excess /= r.energy_scale;
  r.final_energy_change /= r.energy_scale;
  return r;
}

std::string describe(const HardCaseReport& r) {
  return format("%s after %ld steps (dt %.3g .. %.3g s), %ld particles%s%s: finite %d, mass exact %d, inside %d, "
                "rho/rho0 %.5f .. %.5f, penetration %.3f cells, energy excess %.4f (change %.4f) of %.4g J/m, max speed "
                "%.3g m/s, max displacement %.3g m",
                r.finished ? "finished" : "STOPPED", r.steps, r.dt_min, r.dt_max, r.particles,
                r.error.empty() ? "" : ": ", r.error.c_str(), r.finite, r.mass_exact, r.inside_tank, r.min_density,
                r.max_density, r.max_penetration, r.max_energy_excess, r.final_energy_change, r.energy_scale,
                r.max_speed, r.max_displacement);
}

}  // namespace bsmpm::test

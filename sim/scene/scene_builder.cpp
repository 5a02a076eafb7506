#include "scene/scene_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_parameters.hpp"
#include "particles/seeding.hpp"
#include "probes/front_probe.hpp"
#include "probes/material_point.hpp"
#include "probes/pressure_probe.hpp"
#include "probes/wall_reaction_probe.hpp"
#include "scene/effect_registry.hpp"
#include "step/bsmpm_simulation.hpp"
#include "step/effects/gravity.hpp"

namespace bsmpm {

namespace {

// Fills the body's shape with particles. A fluid with initial_stress = "hydrostatic" starts
// at rest under gravity: p = rho0 |g| depth, the depth measured from the body's highest point
// along -g; J follows from the equation of state, and the mass is that of the compressed
// water (m = rho0 V / J).
void seed_body(const SceneDescription& scene, const BodyDescription& desc, BodyId id, Particles& ps,
               Body& body) {
  const Vec2 h = scene.actual_cell_size();
  const SeededPoints pts = seed_particles(desc.shape, scene.domain_min, h / scene.particles_per_cell);
  body.spacing = pts.spacing;
  body.begin = ps.size();
  const double rho = density_of(desc.material);
  const GravityParameters* gravity = scene.effect_parameters<GravityParameters>();
  const auto* fluid = std::get_if<WeaklyCompressibleFluid>(&desc.material);
  const bool incompressible = is_incompressible(desc.material);
  const bool hydrostatic =
      (fluid || incompressible) && desc.initial_stress == InitialStress::kHydrostatic && gravity;
  const Vec2 g = gravity ? gravity->vector() : Vec2::Zero();
  const Vec2 up = hydrostatic ? Vec2(-g / g.norm()) : Vec2(0.0, 1.0);
  double top = -std::numeric_limits<double>::infinity();
  for (const Vec2& x : pts.positions) top = std::max(top, up.dot(x));
  top += 0.5 * (std::abs(up.x()) * pts.spacing.x() + std::abs(up.y()) * pts.spacing.y());

  for (std::size_t k = 0; k < pts.positions.size(); ++k) {
    const Vec2& x = pts.positions[k];
    double J = 1.0, pressure = 0.0;
    if (hydrostatic) {
      pressure = rho * gravity->g * (top - up.dot(x));
      if (fluid) J = fluid->volume_ratio(pressure);  // incompressible water keeps J = 1
    }
    const double V0 = pts.volumes[k] / J;
    ps.push_back(x, rho * V0, V0, id);
    const std::size_t p = ps.size() - 1;
    ps.v[p] = desc.velocity;
    ps.J[p] = J;
    ps.pressure[p] = pressure;
    // An incompressible fluid's stress is its viscous part alone: the projection owns p.
    ps.stress[p] = incompressible ? Mat2::Zero() : Mat2(-pressure * Mat2::Identity());
  }
  body.end = ps.size();
}

// The share of each control point along a wall that a sensor face [a, b] carries: the
// integral of its basis function over the face over its whole integral (method.md §8, eq. S2).
template <int P>
std::vector<double> face_shares(const ClampedBSpline<P>& basis, double a, double b) {
  std::vector<double> share(basis.basis_count(), 0.0);
  basis.add_integrals(a, b, share);
  for (int k = 0; k < basis.basis_count(); ++k) share[k] /= basis.integral(k);
  return share;
}

std::unique_ptr<Probe> make_wall_reaction_probe(const SceneDescription& scene, const ProbeDescription& d) {
  const bool vertical = d.wall == kLeft || d.wall == kRight;
  const int axis = vertical ? 1 : 0;
  const double origin = scene.domain_min[axis], h = scene.actual_cell_size()[axis];
  const int cells = vertical ? scene.cells_y() : scene.cells_x();
  const double a = std::max(d.position - 0.5 * d.size, origin);
  const double b = std::min(d.position + 0.5 * d.size, origin + h * cells);
  std::vector<double> share;
  switch (scene.order) {
    case 1: share = face_shares(ClampedBSpline<1>(origin, h, cells), a, b); break;
    case 2: share = face_shares(ClampedBSpline<2>(origin, h, cells), a, b); break;
    default: share = face_shares(ClampedBSpline<3>(origin, h, cells), a, b); break;
  }
  return std::make_unique<WallReactionProbe>(d.name, d.interval, d.wall, d.position, b - a, std::move(share),
                                             scene.reference);
}

std::unique_ptr<Probe> make_probe(const SceneDescription& scene, const ProbeDescription& d, const Particles& ps,
                                  const std::vector<Body>& bodies) {
  std::vector<int> fluids;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (is_fluid(bodies[b].material)) fluids.push_back(static_cast<int>(b));
  const Vec2 h = scene.actual_cell_size();
  const PressureSensor sensor{d.size, d.depth.value_or(std::min(h.x(), h.y()))};
  switch (d.kind) {
    case ProbeDescription::Kind::kWallPressure: {
      Vec2 centre, normal;
      switch (d.wall) {
        case kLeft: centre = {scene.domain_min.x(), d.position}; normal = {1, 0}; break;
        case kRight: centre = {scene.domain_max.x(), d.position}; normal = {-1, 0}; break;
        case kBottom: centre = {d.position, scene.domain_min.y()}; normal = {0, 1}; break;
        default: centre = {d.position, scene.domain_max.y()}; normal = {0, -1}; break;
      }
      return std::make_unique<PressureProbe>(d.name, d.interval, centre, normal, sensor, fluids, scene.reference,
                                             std::string(wall_side_name(d.wall)) + " wall");
    }
    case ProbeDescription::Kind::kWallReaction:
      return make_wall_reaction_probe(scene, d);
    case ProbeDescription::Kind::kSurfacePressure: {
      MaterialPoint anchor(ps, bodies[*d.body], d.point);
      return std::make_unique<PressureProbe>(d.name, d.interval, anchor, d.normal, sensor, fluids, scene.reference,
                                             "face of " + bodies[*d.body].name);
    }
    case ProbeDescription::Kind::kFront:
      return std::make_unique<FrontProbe>(d.name, d.interval, *d.body, bodies[*d.body].name, d.normal, scene.reference);
    case ProbeDescription::Kind::kMaterialPoint:
      return std::make_unique<MaterialPointProbe>(d.name, d.interval, MaterialPoint(ps, bodies[*d.body], d.point),
                                                  bodies[*d.body].name);
  }
  return nullptr;
}

// Grid fields: without contacts every body shares one field (standard MPM). With contacts
// every body has its own field and interacts only through the declared pairs; a "stick"
// pair of deformable bodies shares one field (single field, as standard MPM). Fields that
// take part in contact also accumulate mass gradients for the normals.
template <int P>
void assign_layers(const std::vector<ContactPair>& contacts, StepState<P>& st) {
  const std::size_t n = st.bodies.size();
  std::vector<int> root(n);
  for (std::size_t b = 0; b < n; ++b) root[b] = contacts.empty() ? 0 : static_cast<int>(b);
  auto find = [&](int b) {
    while (root[b] != b) b = root[b] = root[root[b]];
    return b;
  };
  for (const auto& c : contacts)
    if (c.kind == ContactKind::kStick && !is_rigid(st.bodies[c.body_r].material) &&
        !is_rigid(st.bodies[c.body_s].material))
      root[std::max(find(c.body_r), find(c.body_s))] = std::min(find(c.body_r), find(c.body_s));
  // Number the fields in body order.
  std::vector<int> layer_of_root(n, -1);
  int layers = 0;
  for (std::size_t b = 0; b < n; ++b) {
    const int r = contacts.empty() ? 0 : find(static_cast<int>(b));
    if (layer_of_root[r] < 0) layer_of_root[r] = layers++;
    st.bodies[b].layer = layer_of_root[r];
  }
  st.layers.resize(layers);
  for (const auto& c : contacts)
    if (st.bodies[c.body_r].layer != st.bodies[c.body_s].layer) {
      st.layers[st.bodies[c.body_r].layer].tracks_mass_gradient = true;
      st.layers[st.bodies[c.body_s].layer].tracks_mass_gradient = true;
    }
}

template <int P>
std::unique_ptr<Simulation> build(const SceneDescription& scene) {
  StepState<P> st;
  st.grid = Grid<P>(scene.domain_min, scene.actual_cell_size(), scene.cells_x(), scene.cells_y());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodyDescription& desc = scene.bodies[b];
    Body body;
    body.name = desc.name;
    body.material = desc.material;
    seed_body(scene, desc, static_cast<BodyId>(b), st.particles, body);
    if (body.size() == 0)
      throw SceneError(desc.where, "bodies[" + std::to_string(b) + "].shape",
                       "the shape holds no particle at this grid resolution");
    st.bodies.push_back(std::move(body));
  }
  const ContactParameters* contacts = scene.effect_parameters<ContactParameters>();
  assign_layers(contacts ? contacts->pairs : std::vector<ContactPair>{}, st);
  auto effects = create_effects<P>(scene.effects, st);

  std::vector<std::unique_ptr<Probe>> probes;
  for (const auto& d : scene.probes) probes.push_back(make_probe(scene, d, st.particles, st.bodies));

  return std::make_unique<BsmpmSimulation<P>>(std::move(st), scene.solver, std::move(effects), std::move(probes));
}

}  // namespace

std::unique_ptr<Simulation> build_simulation(const SceneDescription& scene) {
  switch (scene.order) {
    case 1: return build<1>(scene);
    case 2: return build<2>(scene);
    default: return build<3>(scene);
  }
}

}  // namespace bsmpm

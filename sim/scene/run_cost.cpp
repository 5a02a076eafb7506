#include "scene/run_cost.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bspline/clamped_bspline.hpp"
#include "contact/contact_parameters.hpp"
#include "io/particle_fields.hpp"
#include "step/effects/gravity.hpp"

namespace bsmpm {

namespace {

// Particles a body's shape will hold (particles/seeding.cpp): a rectangle is split into whole
// spacings per axis; other shapes hold about area / spacing^2.
double particle_count(const Shape& shape, const Vec2& spacing) {
  if (const auto* r = std::get_if<Rectangle>(&shape)) {
    const Vec2 size = r->max - r->min;
    const double nx = std::max(1.0, std::round(size.x() / spacing.x()));
    const double ny = std::max(1.0, std::round(size.y() / spacing.y()));
    return nx * ny;
  }
  return std::max(1.0, area(shape) / spacing.prod());
}

// Bytes of one value of every particle field with `use` (io/particle_fields).
double field_bytes(unsigned use) {
  double bytes = 0.0;
  for (const ParticleField& f : particle_fields()) {
    if (!(f.use & use)) continue;
    const double size = f.type == FieldType::kUInt16 ? 2.0 : f.type == FieldType::kUInt32 ? 4.0 : 8.0;
    bytes += size * f.components;
  }
  return bytes;
}

// The most components of a particle field with `use`: the writer's buffer holds one field.
int max_components(unsigned use) {
  int most = 0;
  for (const ParticleField& f : particle_fields())
    if (f.use & use) most = std::max(most, f.components);
  return most;
}

}  // namespace

RunCost predict_run_cost(const SceneDescription& scene) {
  RunCost c;
  const Vec2 h = scene.actual_cell_size();
  const Vec2 spacing = h / scene.particles_per_cell;
  for (const BodyDescription& b : scene.bodies) {
    const double n = particle_count(b.shape, spacing);
    c.particles += n;
    if (is_rigid(b.material)) c.rigid_particles += n;
  }

  const ContactParameters* contacts = scene.effect_parameters<ContactParameters>();
  c.grid_fields = contacts && !contacts->pairs.empty() ? static_cast<int>(scene.bodies.size()) : 1;
  c.control_points = double(scene.cells_x() + scene.order) * double(scene.cells_y() + scene.order);

  // Memory of the running step (BsmpmSimulation::memory_use): every particle array, the 1-D
  // weights of one step (2 ints and 4 (P + 1) doubles), the slot of each id and the scatter
  // order (4 + 4 bytes), the sort's keys and order and the first column of each particle
  // (4 + 4 + 4), the buffers the sort permutes through (one Vec2, double, Mat2, id and body
  // each: 62 bytes), the velocity gradients kept by the volume smoothing or projection (and
  // the projection's increments), and the writer's buffer for one field of a frame; per
  // control point and field the mass and five vectors (GridLayer), a mass gradient and a
  // contact slot with contact, a volume with particle shifting, and once the start of each
  // cell's particles in the sort (4), the nine moments of the volume smoothing or the
  // projection's two sums.
  using FluidVolume = SolverSettings::FluidVolume;
  const FluidVolume volume = scene.solver.fluid_volume;
  const double per_particle = field_bytes(kCheckpointState) + 8.0 + 32.0 * (scene.order + 1) + 8.0 + 12.0 + 62.0 +
                              (volume == FluidVolume::kSmoothed ? 32.0 : 0.0) +
                              (volume == FluidVolume::kProjected ? 40.0 : 0.0) + 8.0 * max_components(kInFrames | kInRunHeader);
  const double per_node = c.grid_fields * (8.0 + 5 * 16.0 + (contacts ? 16.0 + 4.0 : 0.0) +
                                           (scene.solver.shifting > 0.0 ? 8.0 : 0.0)) +
                          4.0 + (volume == FluidVolume::kSmoothed ? 72.0 : 0.0) +
                          (volume == FluidVolume::kProjected ? 16.0 : 0.0);
  // The program and its libraries (OSMesa, FFmpeg, HDF5) before the first particle: the peak
  // resident memory of a 64-particle run of the hydrostatic tank is 78 MiB.
  constexpr double kProgramBytes = 78.0 * 1024 * 1024;
  c.memory_bytes = c.particles * per_particle + c.control_points * per_node + kProgramBytes;

  // The fastest signal: a fall from the highest fluid to the floor gives the flow speed
  // sqrt(2 g dz); every body adds its own wave speed (and its initial or prescribed speed).
  const GravityParameters* gravity = scene.effect_parameters<GravityParameters>();
  double top = -1e300;
  for (const BodyDescription& b : scene.bodies)
    if (is_fluid(b.material)) top = std::max(top, bounding_box(b.shape).max.y());
  if (gravity && top > scene.domain_min.y()) c.flow_speed = std::sqrt(2.0 * gravity->g * (top - scene.domain_min.y()));
  for (const BodyDescription& b : scene.bodies) {
    // The wave speed at rest (docs/method.md §7) and the body's initial speed; a rigid body's
    // own prescribed speed instead.
    double speed = signal_speed(b.material, 1.0, b.velocity.norm()) + (is_fluid(b.material) ? c.flow_speed : 0.0);
    // An incompressible fluid carries no sound: its step is the flow's, or the viscous limit's
    // (docs/method.md §12) where that is shorter.
    if (const auto* f = std::get_if<IncompressibleFluid>(&b.material))
      speed = std::max(speed, f->viscous_speed(std::min(h.x(), h.y())));
    if (speed > c.signal_speed) {
      c.signal_speed = speed;
      c.stiffest_body = b.name;
      c.wave_speed = wave_speed(b.material, 1.0);
    }
  }
  const double h_min = std::min(h.x(), h.y());
  c.stable_dt = c.signal_speed > 0.0 ? h_min / c.signal_speed : std::numeric_limits<double>::infinity();  // no waves: no limit
  const TimeStepSettings& t = scene.time;
  if (t.mode == TimeStepSettings::Mode::kFixed) c.first_dt = t.dt;
  else c.first_dt = c.signal_speed > 0.0 ? std::min(t.max_dt, t.cfl * c.stable_dt) : t.max_dt;
  c.frames = std::floor(t.end / scene.frame_interval + 1e-9) + 1.0 +
             (std::fmod(t.end, scene.frame_interval) > 1e-9 * scene.frame_interval ? 1.0 : 0.0);
  c.steps = std::ceil(t.end / c.first_dt) + c.frames;  // a landing on each frame time may add one
  c.particle_steps = c.steps * c.particles;

  // run.h5: the header fields once, the frame fields per frame; probe series in run.h5 and
  // as CSV text (about 16 characters a value); the conservation series per frame.
  double probe_values = 0.0;
  for (const ProbeDescription& p : scene.probes) {
    const double rows = p.interval > 0.0 ? t.end / p.interval + 1.0 : c.steps;
    const double columns = p.kind == ProbeDescription::Kind::kMaterialPoint ? 5.0
                           : p.kind == ProbeDescription::Kind::kFront        ? 3.0
                                                                             : 4.0;
    probe_values += rows * columns;
  }
  constexpr double kConservationColumns = 14.0;
  c.output_bytes = c.particles * field_bytes(kInRunHeader) + c.frames * c.particles * field_bytes(kInFrames) +
                   (probe_values + c.frames * kConservationColumns) * (8.0 + 16.0) + 64.0 * 1024;
  c.checkpoint_bytes = c.particles * field_bytes(kCheckpointState) + probe_values * 8.0 + 64.0 * 1024;
  return c;
}

}  // namespace bsmpm

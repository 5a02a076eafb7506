#include "figure/frame_particles.hpp"

#include <algorithm>
#include <cmath>

namespace bsmpm::render {

FrameParticles load_frame_particles(const RunReader& run, int frame, Field water_field) {
  FrameParticles out;
  out.frame = run.frames().at(static_cast<std::size_t>(frame));
  const auto& body_of = run.particle_bodies();
  const auto& bodies = run.bodies();
  bool any_solid = false;
  for (const auto& b : bodies) any_solid = any_solid || (b.is_solid() && b.count > 0);

  const std::vector<Vec2> position = run.position(frame);
  const std::vector<double> volume = run.volume(frame);
  const std::vector<double> water_value = field_values(run, frame, water_field);
  const std::vector<double> solid_value = any_solid ? field_values(run, frame, Field::kDisplacement) : std::vector<double>{};
  for (std::size_t k = 0; k < position.size(); ++k) {
    const RunBodyInfo& body = bodies[body_of[k]];
    ParticleLayer* layer = body.is_fluid() ? &out.water : body.is_solid() ? &out.solids : nullptr;
    if (!layer) continue;
    layer->position.push_back(position[k]);
    layer->side.push_back(std::sqrt(std::max(volume[k], 0.0)));
    layer->value.push_back(body.is_fluid() ? water_value[k] : solid_value[k]);
  }
  return out;
}

}  // namespace bsmpm::render

// One frame of a run as the painters need it: water and solid particles split into two
// layers, each with position, splat side (sqrt of the current volume) and colour value.
#pragma once

#include <vector>

#include "core/types.hpp"
#include "figure/field.hpp"
#include "io/run_reader.hpp"

namespace bsmpm::render {

struct ParticleLayer {
  std::vector<Vec2> position;  // m
  std::vector<double> side;    // sqrt(volume), m
  std::vector<double> value;   // the layer's field, SI

  std::size_t size() const { return position.size(); }
  bool empty() const { return position.empty(); }
};

struct FrameParticles {
  RunFrameInfo frame;
  ParticleLayer water;   // bodies of type "fluid", coloured by the chosen field
  ParticleLayer solids;  // "elastic" and "rigid" bodies, coloured by displacement
};

FrameParticles load_frame_particles(const RunReader& run, int frame, Field water_field);

}  // namespace bsmpm::render

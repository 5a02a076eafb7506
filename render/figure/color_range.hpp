// Colour ranges fixed for a whole run, so that a colour means the same value in every
// frame of a movie and in every PNG of the run. When neither the command line nor the
// scene's [render] table gives one, a first pass over every frame of the run finds it.
#pragma once

#include "color/color_map.hpp"
#include "figure/field.hpp"
#include "io/run_reader.hpp"

namespace bsmpm::render {

enum class ParticleKind { kWater, kSolid };

// Range of `field` over the particles of `kind` in every frame of the run:
//   water fields  [min(0, lowest 0.5th percentile), highest 99.5th percentile] over the
//                 frames: the impact spikes of a few particles would otherwise wash out
//                 the colours of the whole cloud (values beyond take the end colours)
//   displacement  [0, maximum]
// A zero-width result is widened to one display unit. No particles of the kind: [0, 1].
ValueRange scan_range(const RunReader& run, Field field, ParticleKind kind);

}  // namespace bsmpm::render

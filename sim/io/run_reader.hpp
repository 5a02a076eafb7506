// Reading run files (run.h5) back: frames, bodies, grid, probes. Used by the renderer.
#pragma once

namespace bsmpm {}  // namespace bsmpm

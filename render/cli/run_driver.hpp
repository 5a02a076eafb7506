// Drives a prepared run to its end (a fresh run or a resumed one): progress, frames,
// checkpoints, and how it ends. Completed: the last frame, summary.json, the checkpoint
// removed. Ctrl-C or SIGTERM: a checkpoint of the state reached, exit 130 or 143. No room on
// the disk for what the next step may write: the same stop, the checkpoint when it fits,
// exit 4 (docs/output-format.md, "A full disk"). A numerical instability: a final frame and
// a checkpoint of the failing state (checkpoint_failed.h5; checkpoint.h5 keeps the last good
// one), exit 3.
#pragma once

#include <cmath>
#include <filesystem>

#include "cli/checkpoint_schedule.hpp"
#include "io/checkpoint.hpp"
#include "io/run_writer.hpp"
#include "scene/scene_description.hpp"
#include "step/run_loop.hpp"

namespace bsmpm::cli {

struct RunContext {
  const SceneDescription& scene;
  Simulation& sim;
  RunWriter& writer;
  std::filesystem::path dir;
  int threads = 1;
  bool quiet = false;
  CheckpointSchedule schedule;
  CheckpointScene checkpoint_scene;
  double previous_wall_seconds = 0.0;  // spent before a resume
  double predicted_wall_seconds = std::nan("");  // of the whole run (cli/wall_time_estimate.hpp)
};

inline std::filesystem::path checkpoint_path(const std::filesystem::path& dir) { return dir / "checkpoint.h5"; }
inline std::filesystem::path failed_checkpoint_path(const std::filesystem::path& dir) {
  return dir / "checkpoint_failed.h5";
}

// Returns the exit status (kOk, 128 + the signal, kUnstable, kOutOfSpace); other failures
// throw.
int drive_run(RunContext& ctx, RunLoopState start);

}  // namespace bsmpm::cli

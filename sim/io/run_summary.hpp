// DIR/summary.json: what a run cost and how it ended, written once at its end (also when it
// failed or was interrupted) so that studies and scripts need not open run.h5 for it.
// Layout in docs/output-format.md.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

namespace bsmpm {

struct RunSummary {
  std::string status;              // "completed", "interrupted" or "failed: ..."
  int exit_status = 0;             // the program's exit status
  long steps = 0;
  double time = 0.0;               // simulated time reached [s]
  double end_time = 0.0;           // the scene's end time [s]
  double wall_seconds = 0.0;       // stepping only (not loading or building)
  double predicted_wall_seconds = std::nan("");  // before the start, from the calibration; unknown without one
  int threads = 0;
  int cores = 0;
  std::size_t particles = 0;
  double particle_steps_per_second = 0.0;
  double peak_memory_mb = 0.0;     // peak resident set of the process (getrusage)
  double min_dt = std::nan("");    // s; unknown (null) when the run failed
  double max_dt = std::nan("");
  int frames = 0;
  double checkpoint_time = std::nan("");  // s: the state DIR/checkpoint.h5 holds; none (null) without one
  int checkpoints = 0;                    // written by this session of the run
  double checkpoint_seconds = 0.0;        // the wall time they took
  // The incompressible fluid's pressure solves (docs/method.md §12); 0 and unknown without one.
  long pressure_solves = 0;
  double pressure_iterations_mean = std::nan("");
  int pressure_iterations_max = 0;
  double pressure_residual_max = std::nan("");
  std::string program_version;
  std::string git_revision;
};

// Writes DIR/summary.json through a temporary file, so a reader never sees half of it.
void write_run_summary(const std::string& dir, const RunSummary& summary);

// Reads DIR/summary.json; throws IoError when it is missing or malformed.
RunSummary read_run_summary(const std::string& dir);

// Peak resident set of this process so far [MiB].
double peak_resident_memory_mb();

}  // namespace bsmpm

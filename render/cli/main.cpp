// bsmpm: B-spline material point simulator for dam-break flows against obstacles.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "io/hdf5.hpp"

namespace {

// OpenMP threads spin briefly and then sleep between parallel loops (GOMP_SPINCOUNT=1000,
// the spin libgomp itself uses when a team has more threads than free cores), unless the
// environment says otherwise (OMP_WAIT_POLICY, or GOMP_SPINCOUNT). Spinning long takes the
// time another job on the same cores needs (on 2 cores beside two other jobs a 2-thread step
// of lobovsky_h300 at 2 mm took 114-151 ms with libgomp's default spin, 60-64 ms passive);
// sleeping at once costs a wake-up per parallel loop (the elastic gate at 2 mm on an idle
// machine: 8.3-9.2 ms a step passive, 6.8-8.0 ms with the short spin; beside two other jobs
// 16.5-18.4 and 13.5-18.6 ms; docs/validation.md, speed). libgomp reads its environment once,
// when it is loaded, and has no call to change the policy afterwards (nor does setting the
// variable from the preinit array reach it): the program starts itself again with the
// variable set. If that fails it carries on with libgomp's default.
void default_to_short_spin(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("GOMP_SPINCOUNT", "1000", 1) != 0) return;
  execv("/proc/self/exe", argv);
}

// The exit status of the error that stopped a command (the table in kHelp and the README).
int exit_status_of(const std::exception& e) {
  using namespace bsmpm;
  if (dynamic_cast<const InputError*>(&e) || dynamic_cast<const SceneError*>(&e) || dynamic_cast<const UsageError*>(&e) ||
      dynamic_cast<const ResourceError*>(&e))
    return cli::kBadInput;
  if (dynamic_cast<const NumericalError*>(&e)) return cli::kUnstable;
  if (dynamic_cast<const OutOfSpaceError*>(&e)) return cli::kOutOfSpace;
  return cli::kFailure;
}

const char* kHelp =
    "usage: bsmpm COMMAND [options]\n"
    "\n"
    "B-spline material point method (BSMPM) for dam-break flows striking rigid and elastic\n"
    "obstacles (Hua et al. 2025, Chinese J. Comput. Mech. 42(5):772).\n"
    "\n"
    "commands\n"
    "  run SCENE --out DIR     simulate a scene; frames to DIR/run.h5 (+ .xdmf), probes to CSV\n"
    "  run --resume DIR        continue an interrupted run from its checkpoint, bit for bit\n"
    "  check SCENE             validate a scene and print what a run would do\n"
    "  bench SCENE             time the step: ms per step, particle-steps per second\n"
    "  render RUN.h5 --out DIR draw frames of a run as PNG images (off screen), or a grid\n"
    "                          of frames as one figure (--layout 2x3 --out fig.png)\n"
    "  movie RUN.h5 --out FILE.mp4\n"
    "                          the run as an H.264 movie, in slow motion\n"
    "  compare A.png B.png     image difference metrics (max, RMS, PSNR, SSIM) and a\n"
    "                          diff image; fails beyond a --tolerance\n"
    "  study STUDY.toml        run a parameter study (one job per case) through Snakemake,\n"
    "                          locally or on Slurm; a CSV of metrics and plots\n"
    "  metrics RUN_DIR         a run's metrics as a study defines them, or a probe's series\n"
    "                          through the sensor model (resampled, moving average)\n"
    "\n"
    "  bsmpm COMMAND --help    the options of a command\n"
    "  bsmpm --version         program version\n"
    "\n"
    "exit status (every command)\n"
    "  0    done (compare: within its tolerance)\n"
    "  1    another failure: an I/O error other than a full disk, a study case or the workflow\n"
    "       failed, compare beyond its tolerance or of images of different sizes\n"
    "  2    bad input: an unknown command or option, a scene or study error, an input file\n"
    "       missing, unreadable or damaged, a run refused before it starts (memory, disk, time)\n"
    "  3    numerical instability (run: frames kept, the failing state in checkpoint_failed.h5)\n"
    "  4    out of space (run: stopped between two steps, every file whole, resumable)\n"
    "  130  interrupted by Ctrl-C (SIGINT): what was written is kept, a run resumes\n"
    "  143  interrupted by SIGTERM: as 130\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace bsmpm;
  h5::leave_failed_objects_at_exit();  // before any other HDF5 call (io/hdf5.hpp)
  // A file reaching the size limit (ulimit -f) is a write that fails with EFBIG, handled as a
  // full disk, not a signal that kills the program.
  std::signal(SIGXFSZ, SIG_IGN);
  default_to_short_spin(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kHelp, args.empty() ? stderr : stdout);
    return args.empty() ? cli::kBadInput : cli::kOk;
  }
  if (args[0] == "--version") {
    std::printf("bsmpm %s (%s)\n", kVersion, kGitRevision);
    return cli::kOk;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  using Command = int (*)(const std::vector<std::string>&);
  static const std::pair<const char*, Command> kCommands[] = {
      {"run", cli::command_run},     {"check", cli::command_check},     {"bench", cli::command_bench},
      {"render", cli::command_render}, {"movie", cli::command_movie},   {"compare", cli::command_compare},
      {"study", cli::command_study}, {"metrics", cli::command_metrics},
  };
  try {
    for (const auto& [name, run] : kCommands)
      if (command == name) return run(args);
    throw UsageError("unknown command '" + command + "' (see bsmpm --help)");
  } catch (const std::exception& e) {
    const int status = exit_status_of(e);
    std::fprintf(stderr, "bsmpm: error: %s%s\n", status == cli::kOutOfSpace ? "out of space: " : "", e.what());
    return status;
  }
}

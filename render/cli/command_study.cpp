// bsmpm study STUDY.toml: validates a study, writes its cases (OUT/plan.json) and runs them
// through Snakemake (scripts/workflow/Snakefile), on local cores or on a Slurm cluster, while
// printing the progress of the study as a whole. docs/studies.md.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/study_progress.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "settings/render_options.hpp"
#include "study/study_cases.hpp"
#include "study/study_loader.hpp"
#include "study/study_options.hpp"
#include "study/study_plan.hpp"

namespace bsmpm::cli {

namespace fs = std::filesystem;

namespace {

const char* kHelp =
    "usage: bsmpm study STUDY.toml [--dir OUT] [--cores N] [--slurm [--partition P] [--time-limit MIN]\n"
    "                   [--jobs N]] [--set KEY=VALUE ...] [--axis NAME=V1,V2,...] [--dry-run]\n"
    "                   [--keep-going] [--unlock] [--quiet]\n"
    "\n"
    "Validates the study (every case's scene is loaded with its overrides), writes its cases to\n"
    "OUT/plan.json and runs the missing ones through Snakemake, one job per case, then writes\n"
    "OUT/NAME.csv (a row per case) and the study's plots (OUT/*.png). A case's run lives in\n"
    "OUT/cases/KEY/, KEY a hash of the base scene's text, the case's overrides and the program\n"
    "version: a rerun computes only what is missing, an interrupted study resumes.\n"
    "\n"
    "options\n"
    "  --dir OUT          output directory (default runs/NAME, NAME the study's name)\n"
    "  --cores N          local cores for Snakemake (default: all)\n"
    "  --slurm            submit each case as a Slurm job (profile scripts/workflow/slurm_profile)\n"
    "  --partition P      Slurm partition (default: the profile's)\n"
    "  --time-limit MIN   Slurm time limit per case in minutes (default: the profile's)\n"
    "  --jobs N           Slurm jobs queued at once (default 100)\n"
    "  --set KEY=VALUE    one more override for every case, before the axes' values\n"
    "                     (repeatable), e.g. --set time.end=0.3 to try a study out\n"
    "  --axis NAME=V,...  other values for an axis that has a key, e.g. --axis grid=0.01,0.008;\n"
    "                     for an axis of tables, the values with these labels (--axis setting=shipped)\n"
    "  --dry-run          validate and show which cases would run; run nothing\n"
    "  --keep-going       run the other cases when one fails (the CSV then marks it failed)\n"
    "  --unlock           release OUT after a study that was killed, then stop\n"
    "  --quiet            no progress line\n"
    "\n"
    "exit status: 0 every case done, 1 a case or the workflow failed, 2 bad study or usage,\n"
    "130 interrupted (the same command resumes)\n";

std::string workflow_dir() {
  if (const char* env = std::getenv("BSMPM_WORKFLOW_DIR")) return env;
  return BSMPM_WORKFLOW_DIR;
}

std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

std::string version_line() { return std::string("bsmpm ") + kVersion + " (" + kGitRevision + ")"; }

// Set when Ctrl-C or SIGTERM reached this process while Snakemake ran: the study was
// interrupted, whatever state its cases were caught in (a case whose run had not started
// yet leaves no trace of it).
std::atomic<bool> g_study_interrupted{false};
extern "C" void note_study_interruption(int) { g_study_interrupted.store(true); }

// Runs argv in `dir` with stdout and stderr appended to `log`, calling `tick` about twice a
// second until it ends; returns its exit status (127: could not be started).
int run_child(const std::vector<std::string>& argv, const fs::path& dir, const fs::path& log,
              const std::function<void()>& tick) {
  const pid_t pid = fork();
  if (pid < 0) throw Error("cannot fork: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd < 0 || chdir(dir.c_str()) != 0) _exit(127);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    std::fprintf(stderr, "bsmpm study: cannot run %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  // Ctrl-C reaches the whole process group: Snakemake stops its jobs (and cancels its Slurm
  // jobs); this process notes it, waits for Snakemake to finish doing so and then reports.
  struct sigaction note {}, old_int {}, old_term {};
  note.sa_handler = note_study_interruption;
  sigaction(SIGINT, &note, &old_int);
  sigaction(SIGTERM, &note, &old_term);
  int status = 0;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw Error("waitpid: " + std::string(std::strerror(errno)));
    if (tick) tick();
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string last_lines(const fs::path& path, int count) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::string out;
  for (std::size_t i = lines.size() > std::size_t(count) ? lines.size() - count : 0; i < lines.size(); ++i)
    out += "    " + lines[i] + "\n";
  return out;
}

// The error line a failed run left in its log, else its last line.
std::string failure_reason(const fs::path& log) {
  std::ifstream in(log);
  std::string last, error;
  for (std::string l; std::getline(in, l);) {
    if (!l.empty()) last = l;
    if (l.find("error:") != std::string::npos) error = l;
  }
  return error.empty() ? last : error;
}

}  // namespace

int command_study(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help", "--slurm", "--dry-run", "--keep-going", "--unlock", "--quiet"},
                 {"--dir", "--cores", "--partition", "--time-limit", "--jobs"}, {"--set", "--axis"});
  if (args.help(kHelp)) return kOk;
  if (args.positional().size() != 1) throw UsageError("study expects one study file (see bsmpm study --help)");
  const bool slurm = args.flag("--slurm");
  if (!slurm && (args.has("--partition") || args.has("--time-limit") || args.has("--jobs")))
    throw UsageError("--partition, --time-limit and --jobs apply to --slurm only");
  const long cores = args.integer("--cores", static_cast<long>(std::thread::hardware_concurrency()));
  const long time_limit = args.integer("--time-limit", 0), jobs = args.integer("--jobs", 100);
  if (cores < 1 || jobs < 1 || time_limit < 0) throw UsageError("--cores and --jobs must be >= 1, --time-limit >= 0");

  // Everything is validated before anything is written.
  StudyDescription study = load_study(args.positional()[0]);
  apply_study_options(study, args.all("--set"), args.all("--axis"));
  const std::vector<StudyCase> cases = expand_cases(study, version_line());
  validate_cases(study, cases, {render::render_scene_extension()});

  const fs::path out = fs::absolute(args.option("--dir", "runs/" + study.name)).lexically_normal();
  fs::create_directories(out / "cases");
  const fs::path workflow = workflow_dir();
  const PlanContext context{fs::canonical("/proc/self/exe").string(), version_line()};
  write_if_changed((out / "plan.json").string(), plan_json(study, cases, context));

  std::vector<std::string> snakemake = {"snakemake", "--snakefile", (workflow / "Snakefile").string(),
                                        "--rerun-incomplete", "--rerun-triggers", "mtime"};
  if (args.flag("--unlock")) snakemake.push_back("--unlock");
  if (args.flag("--keep-going")) snakemake.push_back("--keep-going");
  if (args.flag("--dry-run")) snakemake.push_back("--dry-run");
  if (slurm) {
    // Snakemake's Slurm executor reads $USER, which a CI machine may not set.
    if (!std::getenv("USER")) setenv("USER", getuid() == 0 ? "root" : std::to_string(getuid()).c_str(), 1);
    snakemake.insert(snakemake.end(), {"--profile", (workflow / "slurm_profile").string(), "--jobs", std::to_string(jobs)});
    std::vector<std::string> resources;
    if (args.has("--partition")) resources.push_back("case:slurm_partition=" + args.option("--partition"));
    if (time_limit > 0) resources.push_back("case:runtime=" + std::to_string(time_limit));
    if (!resources.empty()) {
      snakemake.push_back("--set-resources");
      snakemake.insert(snakemake.end(), resources.begin(), resources.end());
    }
  } else {
    snakemake.insert(snakemake.end(), {"--cores", std::to_string(cores)});
  }

  std::vector<std::string> keys;
  for (const auto& c : cases) keys.push_back(c.key);
  StudyProgress progress(out, keys, slurm ? 0 : std::max(1, static_cast<int>(cores) / study.threads));
  const StudyStatus before = progress.poll();
  std::printf("study    %s: %zu cases (", study.name.c_str(), cases.size());
  for (std::size_t a = 0; a < study.axes.size(); ++a)
    std::printf("%s%s: %zu", a ? " x " : "", study.axes[a].name.c_str(), study.axes[a].values.size());
  std::printf("), %d done already, in %s\n", before.done, out.string().c_str());
  if (args.flag("--dry-run")) {
    for (const auto& c : cases)
      std::printf("  %s  %-5s  %s\n", c.key.c_str(), progress.state(c.key) == CaseState::kDone ? "done" : "run",
                  describe_case(study, c).c_str());
  }
  std::printf("engine   %s\n", slurm ? "Snakemake, Slurm" : ("Snakemake, " + std::to_string(cores) + " local cores").c_str());
  std::fflush(stdout);

  const fs::path log = out / "snakemake.log";
  { std::ofstream truncate(log); }
  const bool tty = isatty(STDERR_FILENO), quiet = args.flag("--quiet");
  std::string last_printed;
  auto last_time = std::chrono::steady_clock::now() - std::chrono::hours(1);
  auto report = [&](bool final_line) {
    if (quiet) return;
    const std::string line = progress.line(progress.poll());
    const auto now = std::chrono::steady_clock::now();
    // On a terminal the line is rewritten in place; in a log, a line when it changes
    // (at most every 2 s) or every 30 s.
    const bool changed = line.substr(0, line.find("elapsed")) != last_printed.substr(0, last_printed.find("elapsed"));
    if (!tty && !final_line && !(changed && now - last_time > std::chrono::seconds(2)) && now - last_time < std::chrono::seconds(30))
      return;
    std::fprintf(stderr, "%sstudy    %s%s", tty ? "\r" : "", line.c_str(), tty ? (final_line ? "\n" : "   ") : "\n");
    std::fflush(stderr);
    last_printed = line;
    last_time = now;
  };
  const int status = run_child(snakemake, out, log, args.flag("--dry-run") ? std::function<void()>() : [&] { report(false); });
  if (status == 127) throw Error("could not run snakemake (scripts/setup installs it); see " + log.string());
  if (args.flag("--dry-run") || args.flag("--unlock")) {
    std::printf("%s: Snakemake says (%s):\n%s", args.flag("--dry-run") ? "dry run" : "unlock", log.string().c_str(),
                last_lines(log, 12).c_str());
    return status == 0 ? kOk : kFailure;
  }
  report(true);

  const StudyStatus after = progress.poll();
  if (after.interrupted > 0 || g_study_interrupted.load()) {
    std::fprintf(stderr, "bsmpm: the study was interrupted (%d cases stopped, %d done); the same command resumes it\n",
                 after.interrupted, after.done);
    return kInterrupted;
  }
  for (const auto& c : cases) {
    if (progress.state(c.key) != CaseState::kFailed) continue;
    const fs::path case_log = out / "cases" / c.key / "run.log";
    std::fprintf(stderr, "bsmpm: case %s (%s) failed: %s\n    log: %s\n", c.key.c_str(), describe_case(study, c).c_str(),
                 failure_reason(case_log).c_str(), case_log.c_str());
  }
  if (status != 0 && after.failed > 0 && after.done > 0) {
    // The others finished: aggregate what there is, the failed cases marked as such.
    // An argument vector, not a shell line: a study directory may hold spaces or ';'.
    const fs::path csv = out / (study.name + ".csv");
    const std::vector<std::string> aggregate = {python(), (workflow / "aggregate.py").string(),
                                                (out / "plan.json").string(), csv.string(), "--partial"};
    if (run_child(aggregate, out, log, {}) == 0)
      std::printf("wrote    %s (partial: %d failed)\n", csv.c_str(), after.failed);
  }
  if (status != 0) {
    if (after.failed == 0)
      std::fprintf(stderr, "bsmpm: the workflow failed; the end of %s:\n%s", log.c_str(), last_lines(log, 15).c_str());
    return kFailure;
  }
  std::printf("wrote    %s/%s.csv", out.c_str(), study.name.c_str());
  for (const auto& p : study.plots) std::printf(", %s.png", p.name.c_str());
  std::printf("\ndone     %d cases (%d reused, %d computed now)\n", after.done, after.reused, after.done - after.reused);
  return kOk;
}

}  // namespace bsmpm::cli

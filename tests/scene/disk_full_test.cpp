// A full disk: `bsmpm run` under a file-size limit (ulimit -f, SIGXFSZ ignored, as a shell
// user would set it) stops with exit status 4 and a message naming the file, what needed the
// room and the space left, never crashing; every frame written before stays readable (the
// run reader, h5ls, bsmpm metrics and render), the probe CSVs end with whole rows and a
// comment saying where the run stopped, summary.json says so too, and the checkpoint it
// wrote (when one fits) resumes to a result bit-identical to a run that had room.
//
// The limits are those at which bsmpm before the room was kept (main at f9bb5b5) failed
// inside a frame (A 600, A 1300), inside the probe flush of a checkpoint (A 2000, A 2030:
// a new chunk of probe rows at step 1024) and inside the checkpoint (B 800, B 900): each time
// it printed "flush failed" or a failed HDF5 write and crashed with SIGSEGV at exit (HDF5
// closing again objects whose close had failed), and at A 1300, A 2000 and A 2030 it left
// run.h5 unreadable (h5ls: "unable to open file"), every frame lost.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/checkpoint.hpp"
#include "io/hdf5.hpp"
#include "io/run_reader.hpp"
#include "io/run_summary.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

// Scene A: 1,800 particles, 13 frames, a checkpoint every 20 steps (2.4 MiB of run.h5).
// Scene B: 5,000 particles, a checkpoint after every step: a checkpoint (0.9 MiB) is larger
// than run.h5 with its first frame, so a limit between the two is met inside the checkpoint.
std::string scene_args(char scene) {
  const std::string common = " --set output.frame_interval=0.01 --threads 1 --quiet --force";
  return test::scene_path("lobovsky_h300.toml") +
         (scene == 'A' ? " --set grid.cell_size=0.02 --set time.end=0.12 --checkpoint-every 20steps"
                       : " --set grid.cell_size=0.012 --set time.end=0.03 --checkpoint-every 1steps") +
         common;
}

struct Outcome {
  bool exited = false;  // false: killed by a signal (the crash this test is about)
  int status = -1;
  std::string output;
};

// `bsmpm ARGS` with files limited to `kib` KiB, through bash as a user would (bash's ulimit
// counts KiB; dash's, 512-byte blocks).
Outcome run_limited(long kib, const std::string& args, const fs::path& log) {
  const std::string command = "exec bash -c 'ulimit -f " + std::to_string(kib) + " && trap \"\" XFSZ && exec " +
                              std::string(BSMPM_EXECUTABLE) + " " + args + "' > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status), WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::read_text(log)};
}

using test::contains;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A probe CSV cut by a full disk: whole rows of `columns` numbers after the comment and the
// header, and a last comment saying where the run stopped. Returns the data rows.
std::size_t check_stopped_csv(const fs::path& path, std::size_t columns, double stop_time) {
  INFO(path);
  const std::string text = test::read_text(path);
  REQUIRE(!text.empty());
  CHECK(text.back() == '\n');
  const auto lines = lines_of(text);
  REQUIRE(lines.size() >= 3);
  CHECK(lines.front().rfind("# ", 0) == 0);
  CHECK(lines.back().rfind(format("# the run stopped here, at t = %.9g s", stop_time), 0) == 0);
  CHECK(contains(lines.back(), "failed: out of space: "));
  std::size_t rows = 0;
  for (std::size_t k = 2; k + 1 < lines.size(); ++k) {
    std::istringstream row(lines[k]);
    std::size_t fields = 0;
    for (std::string field; std::getline(row, field, ',');) {
      std::size_t used = 0;
      std::stod(field, &used);
      CHECK(used == field.size());
      ++fields;
    }
    CHECK(fields == columns);
    ++rows;
  }
  return rows;
}

// Everything a run stopped by the limit left in `dir` opens and reads back whole; its status
// starts with `status`.
void check_stopped_run(const fs::path& dir, const std::string& status) {
  // summary.json: how and where it ended.
  const RunSummary summary = read_run_summary(dir.string());
  CHECK(summary.exit_status == 4);
  CHECK(summary.status.rfind(status, 0) == 0);
  CHECK(summary.time < summary.end_time);
  // run.h5: every frame's every field, the status and the probe series.
  RunReader run((dir / "run.h5").string());
  CHECK(run.status() == summary.status);
  CHECK(static_cast<int>(run.frames().size()) == summary.frames);
  for (const RunFrameInfo& frame : run.frames()) {
    INFO("frame " << frame.index);
    CHECK(run.position(frame.index).size() == run.particle_count());
    CHECK(run.velocity(frame.index).size() == run.particle_count());
    CHECK(run.displacement(frame.index).size() == run.particle_count());
    CHECK(run.pressure(frame.index).size() == run.particle_count());
    CHECK(run.stress(frame.index).size() == run.particle_count());
    CHECK(run.volume(frame.index).size() == run.particle_count());
  }
  for (const std::string& name : run.probe_names()) {
    const RunProbeSeries series = run.probe(name);
    REQUIRE(series.rows > 0);
    CHECK(check_stopped_csv(dir / (name + ".csv"), series.columns.size(), summary.time) == series.rows);
    CHECK(series.values[(series.rows - 1) * series.columns.size()] == summary.time);  // sampled to the stop
  }
  check_stopped_csv(dir / "conservation.csv", 14, summary.time);
  // The tools: h5ls, and the program's own readers.
  CHECK(std::system(("h5ls -r " + (dir / "run.h5").string() + " > " + (dir.string() + ".h5ls") + " 2>&1").c_str()) == 0);
  CHECK(test::run_program("metrics " + dir.string() + " --series P_z30", dir.string() + ".metrics").status == 0);
  // No half-written file.
  for (const auto& entry : fs::directory_iterator(dir)) CHECK(entry.path().extension() != ".tmp");
}

// A run with room, to compare the resumed ones with.
fs::path reference_run() {
  static const fs::path dir = [] {
    const fs::path d = test::scratch_dir("disk_full_reference") / "run";
    REQUIRE(test::run_program("run " + scene_args('A') + " --out " + d.string(), d.string() + ".log").status == 0);
    return d;
  }();
  return dir;
}

void require_same_results(const fs::path& a, const fs::path& b) {
  for (const char* csv : {"P_z30.csv", "P_z80.csv", "conservation.csv"}) {
    INFO(csv);
    CHECK(test::read_text(a / csv) == test::read_text(b / csv));
  }
  RunReader x((a / "run.h5").string()), y((b / "run.h5").string());
  REQUIRE(x.frames().size() == y.frames().size());
  for (const RunFrameInfo& frame : x.frames()) {
    INFO("frame " << frame.index);
    CHECK(x.position(frame.index) == y.position(frame.index));
    CHECK(x.pressure(frame.index) == y.pressure(frame.index));
    CHECK(x.stress(frame.index) == y.stress(frame.index));
  }
}

}  // namespace

TEST_CASE("A full disk stops the run with every file whole, and it resumes from its checkpoint", "[cli][disk]") {
  struct Case {
    long kib;
    const char* where;  // where bsmpm failed before the room was kept
  };
  const Case c = GENERATE(Case{600, "frame"}, Case{1300, "frame"}, Case{2000, "probe flush"}, Case{2030, "probe flush"});
  INFO("ulimit -f " << c.kib << " (before: failed inside a " << c.where << ")");
  const fs::path dir = test::scratch_dir("disk_full_" + std::to_string(c.kib)) / "run";
  const Outcome r = run_limited(c.kib, "run " + scene_args('A') + " --out " + dir.string(), dir.string() + ".log");
  INFO(r.output);
  REQUIRE(r.exited);
  CHECK(r.status == 4);
  const std::string error = "bsmpm: error: out of space: " + dir.string() +
                            "/run.h5: no room for the next frame and the probe rows until then (about ";
  CHECK(contains(r.output, error));
  CHECK(contains(r.output, " free on its disk, and a file may reach "));
  CHECK(contains(r.output, " (ulimit -f)"));
  CHECK(contains(r.output, "make room, then `bsmpm run --resume " + dir.string() + "` continues from t = "));
  check_stopped_run(dir, "failed: out of space: " + dir.string() + "/run.h5: no room for the next frame");
  // The checkpoint holds the state where the run stopped.
  const RunSummary summary = read_run_summary(dir.string());
  const Checkpoint checkpoint = read_checkpoint((dir / "checkpoint.h5").string());
  CHECK(checkpoint.counters.time == summary.time);
  CHECK(summary.checkpoint_time == summary.time);
  // With room again, the run continues to the result it would have had.
  REQUIRE(test::run_program("run --resume " + dir.string() + " --quiet --threads 1", dir.string() + ".resume").status == 0);
  require_same_results(reference_run(), dir);
}

TEST_CASE("A checkpoint that does not fit stops the run, its frames whole", "[cli][disk]") {
  const long kib = GENERATE(800L, 900L);
  INFO("ulimit -f " << kib << " (before: failed inside the checkpoint)");
  const fs::path dir = test::scratch_dir("disk_full_checkpoint_" + std::to_string(kib)) / "run";
  const Outcome r = run_limited(kib, "run " + scene_args('B') + " --out " + dir.string(), dir.string() + ".log");
  INFO(r.output);
  REQUIRE(r.exited);
  CHECK(r.status == 4);
  CHECK(contains(r.output, "bsmpm: error: out of space: " + dir.string() +
                               "/checkpoint.h5: no room for the checkpoint (about "));
  CHECK(contains(r.output, "bsmpm: no room for a checkpoint"));
  CHECK(contains(r.output, "the run cannot be resumed"));
  check_stopped_run(dir, "failed: out of space: " + dir.string() + "/checkpoint.h5: no room for the checkpoint");
  CHECK(!fs::exists(dir / "checkpoint.h5"));
  CHECK(std::isnan(read_run_summary(dir.string()).checkpoint_time));
  // A render of the frame written before the limit.
  CHECK(test::run_program("render " + (dir / "run.h5").string() + " --frames 0 --quiet --size 320x180 --out " +
                              dir.string() + ".png",
                          dir.string() + ".render")
            .status == 0);
  CHECK(fs::file_size(dir.string() + ".png") > 0);
}

TEST_CASE("run and check refuse output that will not fit, before anything is written, unless --force", "[cli][disk]") {
  // Scene A's run.h5 grows to about 2.4 MiB (predicted 2.7 MiB).
  const fs::path dir = test::scratch_dir("disk_full_refused") / "run";
  const std::string args = test::scene_path("lobovsky_h300.toml") +
                           " --set grid.cell_size=0.02 --set time.end=0.12 --set output.frame_interval=0.01 --out " +
                           dir.string();
  for (const std::string& command : {"run " + args + " --quiet", "check " + args}) {
    INFO(command);
    const Outcome r = run_limited(1000, command, dir.string() + ".log");
    INFO(r.output);
    REQUIRE(r.exited);
    CHECK(r.status == 2);
    CHECK(contains(r.output, "lobovsky_h300.toml: run.h5 grows to about "));
    CHECK(contains(r.output, ", and a file may reach 1000 KiB (ulimit -f). "));
    CHECK(contains(r.output, "bsmpm run --force starts anyway and stops, resumable, when the disk is full"));
    CHECK(!fs::exists(dir));
  }
  const Outcome forced = run_limited(1000, "run " + args + " --quiet --force", dir.string() + ".log");
  INFO(forced.output);
  CHECK(forced.status == 4);
  CHECK(contains(forced.output, "warning  run.h5 grows to about "));
}

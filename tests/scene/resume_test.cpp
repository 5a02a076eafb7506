// Checkpoint and resume through the program: a run stopped by SIGINT or SIGTERM, or killed
// (SIGKILL) between two checkpoints, and resumed with bsmpm run --resume, ends with frames,
// probe series, conservation rows and CSV files bit-identical to those of the run that was
// never interrupted; frames and rows continue without a gap or a duplicate. The scene carries
// sensors of the walls' reaction besides the particle probes.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "io/hdf5.hpp"
#include "io/particle_fields.hpp"
#include "scene/signalled_run.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kSceneArgs = {"--set", "grid.cell_size=0.01", "--set", "output.frame_interval=0.01",
                                             "--set", "time.end=0.12", "--quiet", "--threads", "1"};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The Lobovsky tank with two sensors of the walls' reaction added (the water presses on the
// floor and the left wall from the start): they read the last step's wall impulses, which a
// resumed run must rebuild exactly from its first step on.
std::string scene_with_reaction_probes() {
  static const std::string path = [] {
    const fs::path p = test::scratch_dir("resume_scene") / "lobovsky_h300_reaction.toml";
    std::ofstream(p) << read_text(test::scene_path("lobovsky_h300.toml"))
                     << "\n[[probes]]\nname = \"R_floor\"\ntype = \"wall_reaction\"\nwall = \"bottom\"\n"
                        "position = 0.3\nsize = 0.6\n"
                        "\n[[probes]]\nname = \"R_left\"\ntype = \"wall_reaction\"\nwall = \"left\"\n"
                        "position = 0.1\nsize = 0.2\n";
    return p.string();
  }();
  return path;
}

std::vector<std::string> run_args(const fs::path& dir, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> a = {"run", scene_with_reaction_probes(), "--out", dir.string()};
  a.insert(a.end(), kSceneArgs.begin(), kSceneArgs.end());
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

std::vector<unsigned char> dataset_bytes(hid_t parent, const std::string& name) {
  const std::vector<double> v = h5::read_doubles(parent, name);
  std::vector<unsigned char> out(v.size() * sizeof(double));
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size());
  return out;
}

// Every frame (each particle field of the table that frames hold, and time, step, dt), every
// probe series and the conservation series, compared bit for bit; and the CSV files.
void require_identical_runs(const fs::path& a, const fs::path& b) {
  h5::Handle fa = h5::open_file((a / "run.h5").string()), fb = h5::open_file((b / "run.h5").string());
  CHECK(h5::get_string_attribute(fb, "status") == "completed");
  CHECK(h5::get_long_attribute(fa, "steps") == h5::get_long_attribute(fb, "steps"));
  h5::Handle ga = h5::open_group(fa, "frames"), gb = h5::open_group(fb, "frames");
  const auto names = h5::children(ga);
  REQUIRE(names.size() == 13);  // t = 0, 0.01, ..., 0.12: no gap, no duplicate
  REQUIRE(h5::children(gb) == names);
  for (const auto& name : names) {
    h5::Handle x = h5::open_group(ga, name), y = h5::open_group(gb, name);
    for (const char* attr : {"time", "dt"}) CHECK(h5::get_double_attribute(x, attr) == h5::get_double_attribute(y, attr));
    CHECK(h5::get_long_attribute(x, "step") == h5::get_long_attribute(y, "step"));
    for (const ParticleField& field : particle_fields())
      if (field.has(kInFrames)) {
        INFO("frame " << name << ", field " << field.name);
        CHECK(dataset_bytes(x, std::string(field.name)) == dataset_bytes(y, std::string(field.name)));
      }
  }
  h5::Handle pa = h5::open_group(fa, "probes"), pb = h5::open_group(fb, "probes");
  const auto probes = h5::children(pa);
  REQUIRE(std::count(probes.begin(), probes.end(), "R_floor") == 1);
  for (const auto& probe : probes) {
    INFO("probe " << probe);
    CHECK(dataset_bytes(pa, probe) == dataset_bytes(pb, probe));
    CHECK(read_text(a / (probe + ".csv")) == read_text(b / (probe + ".csv")));
  }
  CHECK(dataset_bytes(fa, "conservation") == dataset_bytes(fb, "conservation"));
  CHECK(h5::dataset_shape(fb, "conservation")[0] == names.size());
  CHECK(read_text(a / "conservation.csv") == read_text(b / "conservation.csv"));
  CHECK(!fs::exists(b / "checkpoint.h5"));  // removed once the run completed
  CHECK(!fs::exists(b / "checkpoint.h5.tmp"));
}

fs::path uninterrupted() {
  static const fs::path dir = [] {
    const fs::path d = test::scratch_dir("resume_reference") / "run";
    REQUIRE(WEXITSTATUS(test::run_signalled(run_args(d))) == 0);
    return d;
  }();
  return dir;
}

// Frames on disk, as the XDMF sidecar lists them.
int frames_listed(const fs::path& dir) {
  const std::string x = read_text(dir / "run.xdmf");
  int n = 0;
  for (auto at = x.find("<Grid Name=\"frame"); at != std::string::npos; at = x.find("<Grid Name=\"frame", at + 1)) ++n;
  return n;
}

int resume(const fs::path& dir) {
  const int status = test::run_signalled({"run", "--resume", dir.string(), "--quiet", "--threads", "1"});
  REQUIRE(WIFEXITED(status));
  return WEXITSTATUS(status);
}

}  // namespace

TEST_CASE("A run stopped by SIGINT or SIGTERM resumes bit for bit", "[cli][checkpoint]") {
  const int signal = GENERATE(SIGINT, SIGTERM);
  const fs::path dir = test::scratch_dir(signal == SIGINT ? "resume_sigint" : "resume_sigterm") / "run";
  // Signalled once 4 of the 13 frames are on disk: the 9 left take far longer than a poll.
  const int status = test::run_signalled(run_args(dir), signal, [&] { return frames_listed(dir) >= 4; });
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 128 + signal);  // 130 for SIGINT, 143 for SIGTERM
  REQUIRE(fs::exists(dir / "checkpoint.h5"));  // written when stopped
  CHECK(resume(dir) == 0);
  require_identical_runs(uninterrupted(), dir);
}

TEST_CASE("A run killed between checkpoints resumes from the last one bit for bit", "[cli][checkpoint]") {
  const fs::path dir = test::scratch_dir("resume_sigkill") / "run";
  // Killed some frames after the first checkpoint: frames, probe rows and CSV lines written
  // after it must go, and come back the same.
  const int status = test::run_signalled(run_args(dir, {"--checkpoint-every", "0.03s"}), SIGKILL, [&] {
    return fs::exists(dir / "checkpoint.h5") && frames_listed(dir) >= 6;
  });
  REQUIRE(WIFSIGNALED(status));
  // As if the kill had come while the next checkpoint was being written: its temporary is
  // half there, and the last whole checkpoint is the one to resume from.
  std::ofstream(dir / "checkpoint.h5.tmp") << "half a checkpoint";
  CHECK(resume(dir) == 0);
  require_identical_runs(uninterrupted(), dir);
  // Resuming a completed run is refused.
  CHECK(resume(dir) == 2);
}

TEST_CASE("A run killed without any checkpoint option resumes from its periodic checkpoint bit for bit", "[cli][checkpoint]") {
  // Checkpoints come every 10 minutes of wall time unless told otherwise; a site may set its
  // own default in BSMPM_CHECKPOINT_EVERY, as here (0.3 s, so that the test need not run for
  // 10 minutes). Killed some frames after the first one; nothing on the command line asks
  // for a checkpoint.
  const fs::path dir = test::scratch_dir("resume_default") / "run";
  const int status = test::run_signalled(
      run_args(dir), SIGKILL, [&] { return fs::exists(dir / "checkpoint.h5") && frames_listed(dir) >= 6; },
      "BSMPM_CHECKPOINT_EVERY=0.005min");
  REQUIRE(WIFSIGNALED(status));
  CHECK(resume(dir) == 0);
  require_identical_runs(uninterrupted(), dir);
}

TEST_CASE("An incompressible run killed between checkpoints resumes bit for bit", "[cli][checkpoint][incompressible]") {
  // The pressure solve starts from the last step's pressure (method.md §12): state beyond the
  // particles that the checkpoint must hold for the resumed run to find the same pressures.
  auto args = [](const fs::path& dir, const std::vector<std::string>& extra) {
    std::vector<std::string> a = {"run", test::scene_path("martin_moyce_incompressible.toml"), "--out", dir.string(),
                                  "--set", "grid.cell_size=0.0025", "--set", "time.end=0.1", "--quiet",
                                  "--threads", "1"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const fs::path reference = test::scratch_dir("resume_incompressible_reference") / "run";
  REQUIRE(WEXITSTATUS(test::run_signalled(args(reference, {}))) == 0);
  const fs::path dir = test::scratch_dir("resume_incompressible") / "run";
  const int status = test::run_signalled(args(dir, {"--checkpoint-every", "0.03s"}), SIGKILL, [&] {
    return fs::exists(dir / "checkpoint.h5") && frames_listed(dir) >= 5;
  });
  REQUIRE(WIFSIGNALED(status));
  CHECK(resume(dir) == 0);
  h5::Handle fa = h5::open_file((reference / "run.h5").string()), fb = h5::open_file((dir / "run.h5").string());
  h5::Handle ga = h5::open_group(fa, "frames"), gb = h5::open_group(fb, "frames");
  const auto names = h5::children(ga);
  REQUIRE(names.size() == 11);
  REQUIRE(h5::children(gb) == names);
  for (const auto& name : names) {
    h5::Handle x = h5::open_group(ga, name), y = h5::open_group(gb, name);
    for (const char* field : {"position", "velocity", "pressure", "volume"}) {
      INFO("frame " << name << ", field " << field);
      CHECK(dataset_bytes(x, field) == dataset_bytes(y, field));
    }
  }
  CHECK(dataset_bytes(h5::open_group(fa, "probes"), "front") == dataset_bytes(h5::open_group(fb, "probes"), "front"));
}

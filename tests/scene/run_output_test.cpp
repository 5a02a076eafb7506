// End to end through the program: bsmpm run writes run.h5, run.xdmf and the probe CSVs;
// refuses to overwrite a run; keeps the frames of an interrupted or failed run.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>
#include <tuple>

#include "io/hdf5.hpp"
#include "scene/signalled_run.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

// A directory for one run: the run itself creates it.
fs::path fresh_dir(const std::string& name) { return test::scratch_dir(name) / "run"; }

int run_program(const std::string& args, const fs::path& log) { return test::run_program(args, log).status; }
using test::read_text;

// Frames in a run file whose datasets read back completely.
int readable_frames(const fs::path& h5, std::size_t particles) {
  h5::Handle f = h5::open_file(h5.string());
  h5::Handle frames = h5::open_group(f, "frames");
  int n = 0;
  for (const auto& name : h5::children(frames)) {
    h5::Handle g = h5::open_group(frames, name);
    if (h5::read_doubles(g, "position").size() == 2 * particles && h5::read_doubles(g, "pressure").size() == particles)
      ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("bsmpm run writes the run file, the XDMF sidecar and the probe CSVs", "[cli][output]") {
  const fs::path dir = fresh_dir("hydrostatic");
  const std::string scene = test::scene_path("hydrostatic_tank.toml");
  REQUIRE(run_program("run " + scene + " --out " + dir.string() + " --quiet --set time.end=0.02 --set output.frame_interval=0.01",
                      dir.string() + ".log") == 0);
  REQUIRE(fs::exists(dir / "run.h5"));
  REQUIRE(fs::exists(dir / "run.xdmf"));
  h5::Handle f = h5::open_file((dir / "run.h5").string());
  CHECK(h5::get_string_attribute(f, "status") == "completed");
  CHECK(h5::get_string_attribute(f, "format") == "bsmpm-run");
  CHECK(h5::get_long_attribute(f, "frames_written") == 3);  // t = 0, 0.01, 0.02
  h5::Handle prov = h5::open_group(f, "provenance");
  CHECK(h5::get_string_attribute(prov, "scene_text") == read_text(scene));
  CHECK(h5::get_string_attribute(prov, "effective_scene").find("end = 0.02") != std::string::npos);
  h5::Handle particles = h5::open_group(f, "particles");
  const std::size_t n = h5::read_uint16(particles, "body").size();
  CHECK(n == 6400);
  CHECK(readable_frames(dir / "run.h5", n) == 3);
  h5::Handle frame = h5::open_group(h5::open_group(f, "frames"), "000002");
  CHECK(h5::get_double_attribute(frame, "time") == Approx(0.02));
  CHECK(h5::dataset_shape(frame, "stress") == std::vector<std::size_t>{n, 3});
  // Units in the file: every particle dataset has its own, the probes and conservation series
  // one per column.
  for (const auto& [group, name, unit] : std::vector<std::tuple<hid_t, std::string, std::string>>{
           {frame, "position", "m"}, {frame, "velocity", "m/s"}, {frame, "pressure", "Pa"}, {frame, "stress", "Pa"},
           {frame, "volume", "m2"}, {particles, "mass", "kg/m"}, {particles, "body", "1"}}) {
    INFO(name);
    h5::Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), name);
    CHECK(h5::get_string_attribute(set, "units") == unit);
  }
  {
    h5::Handle stress(H5Dopen2(frame, "stress", H5P_DEFAULT), "stress");
    CHECK(h5::get_string_attribute(stress, "components") == "xx,yy,xy");
    h5::Handle conservation(H5Dopen2(f, "conservation", H5P_DEFAULT), "conservation");
    CHECK(h5::get_string_attribute(conservation, "units") == "s,1,kg/m,kg/s,kg/s,J/m,J/m,J/m,J/m,J/m,J/m,J/m,J/m,J/m");
  }

  // One CSV per probe with a header row of names and units (a number without unit bare), and
  // the same rows in run.h5, whose columns and units are attributes.
  const std::string csv = read_text(dir / "P_depth100.csv");
  CHECK(csv.find("\nt [s],T*,P [Pa],P*\n") != std::string::npos);
  CHECK(read_text(dir / "conservation.csv").find("\nt [s],step,mass [kg/m],momentum_x [kg/s],") != std::string::npos);
  h5::Handle probes = h5::open_group(f, "probes");
  {
    h5::Handle set(H5Dopen2(probes, "P_depth100", H5P_DEFAULT), "probe");
    CHECK(h5::get_string_attribute(set, "columns") == "t,T*,P,P*");
    CHECK(h5::get_string_attribute(set, "units") == "s,1,Pa,1");
  }
  const auto shape = h5::dataset_shape(probes, "P_depth100");
  REQUIRE(shape.size() == 2);
  CHECK(shape[1] == 4);
  const auto lines = std::count(csv.begin(), csv.end(), '\n');
  CHECK(static_cast<std::size_t>(lines) == shape[0] + 2);  // comment + header + rows
  const std::string xdmf = read_text(dir / "run.xdmf");
  CHECK(xdmf.find("run.h5:/frames/000002/position") != std::string::npos);
  // The stress as its three named components, each a hyperslab (column c) of the dataset;
  // no Vector of three components, which ParaView would show as x, y, z.
  const std::string count = std::to_string(n);
  for (int c = 0; c < 3; ++c) {
    const std::string name = std::string("stress_") + (c == 0 ? "xx" : c == 1 ? "yy" : "xy");
    const std::string item = "<Attribute Name=\"" + name + "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                             "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"" + count + " 1\" Type=\"HyperSlab\">\n"
                             "      <DataItem Dimensions=\"3 2\" Format=\"XML\">0 " + std::to_string(c) + " 1 1 " + count +
                             " 1</DataItem>\n"
                             "      <DataItem Dimensions=\"" + count + " 3\" NumberType=\"Float\" Precision=\"8\" "
                             "Format=\"HDF\">run.h5:/frames/000002/stress</DataItem>";
    INFO(item);
    CHECK(xdmf.find(item) != std::string::npos);
  }
  CHECK(xdmf.find("<Attribute Name=\"stress\"") == std::string::npos);
}

TEST_CASE("bsmpm run refuses to overwrite a run without --force", "[cli][output]") {
  const fs::path dir = fresh_dir("twice");
  const std::string args = "run " + test::scene_path("hydrostatic_tank.toml") + " --out " + dir.string() +
                           " --quiet --set time.end=0.005 --set output.frame_interval=0.005";
  REQUIRE(run_program(args, dir.string() + ".log") == 0);
  const auto before = fs::last_write_time(dir / "run.h5");
  CHECK(run_program(args, dir.string() + ".log") == 2);
  CHECK(read_text(dir.string() + ".log").find("holds a run already") != std::string::npos);
  CHECK(fs::last_write_time(dir / "run.h5") == before);
  CHECK(run_program(args + " --force", dir.string() + ".log") == 0);
}

namespace {

// Starts `bsmpm run` on the coarse Lobovsky tank with frequent frames (525 of them to
// t = 1.05 s), sends `signal` once four frames are on disk; returns the wait status.
int run_and_signal(const fs::path& dir, int signal) {
  const std::string scene = test::scene_path("lobovsky_h300.toml");
  std::string xdmf;
  const int status = test::run_signalled(
      {"run", scene, "--out", dir.string(), "--quiet", "--threads", "1", "--set", "grid.cell_size=0.01", "--set",
       "output.frame_interval=0.002"},
      signal, [&] {
        if (fs::exists(dir / "run.xdmf")) xdmf = read_text(dir / "run.xdmf");
        return xdmf.find("frame 000003") != std::string::npos;
      });
  REQUIRE(xdmf.find("frame 000003") != std::string::npos);
  return status;
}

}  // namespace

TEST_CASE("Ctrl-C stops a run and keeps its frames", "[cli][output]") {
  const fs::path dir = fresh_dir("interrupted");
  const int status = run_and_signal(dir, SIGINT);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  h5::Handle f = h5::open_file((dir / "run.h5").string());
  CHECK(h5::get_string_attribute(f, "status") == "interrupted");
  const long written = h5::get_long_attribute(f, "frames_written");
  CHECK(written >= 4);
  const std::size_t n = h5::read_uint16(h5::open_group(f, "particles"), "body").size();
  CHECK(readable_frames(dir / "run.h5", n) == written);
}

TEST_CASE("A killed run (SIGKILL, as in a crash) keeps the frames it flushed", "[cli][output]") {
  const fs::path dir = fresh_dir("killed");
  const int status = run_and_signal(dir, SIGKILL);
  REQUIRE(WIFSIGNALED(status));
  // The file opens; every frame counted at the last flush reads back whole.
  h5::Handle f = h5::open_file((dir / "run.h5").string());
  CHECK(h5::get_string_attribute(f, "status") == "running");
  const long written = h5::get_long_attribute(f, "frames_written");
  CHECK(written >= 4);
  const std::size_t n = h5::read_uint16(h5::open_group(f, "particles"), "body").size();
  CHECK(readable_frames(dir / "run.h5", n) >= written);
}

TEST_CASE("A numerically unstable run stops with exit code 3 and keeps its frames", "[cli][output]") {
  // A fixed step 40 times the acoustic CFL limit of this grid blows up within a few steps.
  const fs::path dir = fresh_dir("unstable");
  std::string text = read_text(test::scene_path("hydrostatic_tank.toml"));
  const auto cfl = text.find("cfl = 0.3");
  REQUIRE(cfl != std::string::npos);
  text.replace(cfl, 9, "dt = 2e-3");
  const auto max_dt = text.find("max_dt = 1.0e-3");
  REQUIRE(max_dt != std::string::npos);
  text.erase(max_dt, 15);
  const fs::path scene = dir.string() + ".toml";
  std::ofstream(scene) << text;
  const int code = run_program("run " + scene.string() + " --out " + dir.string() + " --quiet", dir.string() + ".log");
  CHECK(code == 3);
  const std::string log = read_text(dir.string() + ".log");
  CHECK(log.find("numerical instability") != std::string::npos);
  h5::Handle f = h5::open_file((dir / "run.h5").string());
  CHECK(h5::get_string_attribute(f, "status").rfind("failed: numerical instability", 0) == 0);
  CHECK(h5::get_long_attribute(f, "frames_written") >= 1);  // the initial state at least
}

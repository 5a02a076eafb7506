// bsmpm render and movie end to end on synthetic runs: the images and the movie they
// write, deterministic output, and bad input that fails clearly and leaves nothing behind.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "image/png_file.hpp"
#include "io/hdf5.hpp"
#include "test_support.hpp"
#include "unit/render/synthetic_run.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

const fs::path& scratch() { return test::scratch_root("render_cli"); }

fs::path fresh_dir(const std::string& name) {
  const fs::path d = scratch() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

using Result = test::ProgramResult;  // status -1: it did not exit (a signal)

Result run_program(const std::string& args) {
  Result r = test::run_program(args, scratch() / "program.log");
  REQUIRE(r.status != -1);
  return r;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Files in `dir`, hidden (temporary) ones included.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("bsmpm render writes one PNG per selected frame, the same bytes every time", "[render][cli]") {
  const fs::path dir = fresh_dir("frames");
  const std::string run = test::write_dam_break_run(dir / "run", true, 4);
  const fs::path out = dir / "images";
  Result r = run_program("render " + run + " --frames 0,-1 --size 320x180 --out " + out.string() + " --quiet");
  REQUIRE(r.status == 0);
  CHECK(listing(out) == std::vector<std::string>{"pressure_000000.png", "pressure_000003.png"});
  const render::Image image = render::read_png((out / "pressure_000003.png").string());
  CHECK(image.width() == 320);
  CHECK(image.height() == 180);
  CHECK(r.output.find("range    water pressure: 0 .. 1.93") != std::string::npos);
  CHECK(r.output.find("range    solid displacement: 0 .. 11.89 mm") != std::string::npos);

  const std::string first = read_bytes(out / "pressure_000003.png");
  REQUIRE(run_program("render " + run + " --times 0.15 --size 320x180 --out " + out.string() + " --quiet").status == 0);
  CHECK(read_bytes(out / "pressure_000003.png") == first);

  // Frames chosen by T*: T* = t sqrt(g/H), H = 0.2 m; frame 2 is at t = 0.1 s.
  const double t_star = 0.1 * std::sqrt(9.81 / 0.2);
  r = run_program("render " + run + " --times-star " + std::to_string(t_star) + " --out " + (dir / "one.png").string() +
                  " --size 400x300 --field velocity --colormap jet --quiet");
  REQUIRE(r.status == 0);
  CHECK(render::read_png((dir / "one.png").string()).height() == 300);

  // A grid figure: height fitted to the panels.
  r = run_program("render " + run + " --layout 2x2 --out " + (dir / "grid.png").string() + " --size 640 --quiet");
  REQUIRE(r.status == 0);
  const render::Image grid = render::read_png((dir / "grid.png").string());
  CHECK(grid.width() == 640);
  CHECK(grid.height() % 2 == 0);
  CHECK(grid.height() < 640);
  fs::remove_all(scratch());
}

TEST_CASE("bsmpm render fails clearly on bad input and writes nothing", "[render][cli]") {
  const fs::path dir = fresh_dir("bad");
  const std::string run = test::write_dam_break_run(dir / "run", false, 2);
  const fs::path out = dir / "out";
  const std::string not_run = (dir / "other.h5").string();
  { h5::Handle f = h5::create_file(not_run); }

  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"render " + (dir / "missing.h5").string() + " --out " + out.string(), "missing.h5: no such file"},
      {"render " + not_run + " --out " + out.string(), "other.h5: not a bsmpm run file"},
      {"render " + run + " --field density --out " + out.string(), "unknown field 'density'"},
      {"render " + run + " --frames 5 --out " + out.string(), "no frame 5"},
      {"render " + run + " --out " + (dir / "x.png").string(), "2 frames are selected"},
      {"render " + run + " --frames 0 --out " + (out / "x.png").string(), "does not exist"},
      {"render " + run + " --size 10x10 --out " + out.string(), "--size expects"},
      {"movie " + run + " --out " + (dir / "m.mp4").string() + " --field density", "unknown field 'density'"},
      {"movie " + not_run + " --out " + (dir / "m.mp4").string(), "not a bsmpm run file"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const Result r = run_program(c.args);
    CHECK(r.status == 2);
    CHECK(r.output.find("bsmpm: error:") != std::string::npos);
    CHECK(r.output.find(c.message) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(dir / "m.mp4"));
  }
  // Only the inputs are left: no partial files.
  CHECK(listing(dir) == std::vector<std::string>{"other.h5", "run"});
  fs::remove_all(scratch());
}

TEST_CASE("bsmpm movie: 10 frames read back by ffprobe as 10 frames of the right size and length",
          "[render][cli][movie]") {
  const fs::path dir = fresh_dir("movie");
  // 10 frames 0.05 s apart; slow motion x2 at 10 fps: each run frame is one movie frame.
  test::SyntheticSimulation sim(test::tank_grid(0.6, 0.3, 0.01));
  sim.add_body("water", WeaklyCompressibleFluid{}, test::lattice({0.0, 0.0}, {0.2, 0.2}, 0.005), 0.005);
  const std::string run = test::write_synthetic_run(dir / "run", sim, 10, 0.05, [](test::SyntheticSimulation& s, int k) {
    Particles& p = s.state();
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.x[i] = p.x0[i] + Vec2(0.02 * k * (1.0 - p.x0[i].y() / 0.2), 0.0);
      p.pressure[i] = 9810.0 * (0.2 - p.x0[i].y());
    }
  });
  const fs::path movie = dir / "run.mp4";
  const Result r = run_program("movie " + run + " --out " + movie.string() + " --fps 10 --slowmo 2 --size 320x180 --quiet");
  REQUIRE(r.status == 0);
  CHECK(r.output.find("10 frames at 10 fps = 1.00 s, 10 run frames") != std::string::npos);
  REQUIRE(fs::exists(movie));
  CHECK(listing(dir) == std::vector<std::string>{"run", "run.mp4"});  // no temporary file left

  const fs::path probe = dir / "ffprobe.txt";
  const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                          "stream=nb_read_frames,width,height,duration,pix_fmt -of csv=p=0 " +
                          movie.string() + " > " + probe.string();
  REQUIRE(std::system(cmd.c_str()) == 0);
  std::ifstream in(probe);
  std::string line;
  std::getline(in, line);
  // Fields in ffprobe's order: width, height, pix_fmt, duration, nb_read_frames.
  std::stringstream fields(line);
  std::vector<std::string> f;
  for (std::string item; std::getline(fields, item, ',');) f.push_back(item);
  REQUIRE(f.size() == 5);
  CHECK(f[0] == "320");
  CHECK(f[1] == "180");
  CHECK(f[2] == "yuv420p");
  CHECK(std::stod(f[3]) == Approx(1.0));
  CHECK(f[4] == "10");

  // Slow motion x4 holds each run frame for two movie frames.
  const Result slow = run_program("movie " + run + " --out " + movie.string() + " --fps 10 --slowmo 4 --size 320x180 --quiet");
  REQUIRE(slow.status == 0);
  CHECK(slow.output.find("19 frames at 10 fps = 1.90 s, 10 run frames") != std::string::npos);
  fs::remove_all(scratch());
}

// RunReader reads back what RunWriter wrote, and names the file in every error.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/hdf5.hpp"
#include "io/run_reader.hpp"
#include "test_support.hpp"
#include "unit/render/synthetic_run.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {
fs::path temp_dir(const std::string& name) { return test::scratch_dir("reader_" + name); }
}  // namespace

TEST_CASE("RunReader reads frames, bodies, grid and reference scales as written", "[render][reader]") {
  const fs::path dir = temp_dir("gate");
  const std::string path = test::write_dam_break_run(dir, true, 3, "[render]\nfield = \"velocity\"\n");
  const RunReader run(path);
  CHECK(run.path() == path);
  CHECK(run.status() == "completed");
  CHECK(run.title() == "synthetic gate");
  CHECK(run.effective_scene() == "[render]\nfield = \"velocity\"\n");

  REQUIRE(run.frames().size() == 3);
  CHECK(run.frames()[2].index == 2);
  CHECK(run.frames()[2].group == "000002");
  CHECK(run.frames()[2].time == Approx(0.1));
  CHECK(run.frames()[2].step == 2);

  REQUIRE(run.bodies().size() == 2);
  const RunBodyInfo& water = run.bodies()[0];
  const RunBodyInfo& gate = run.bodies()[1];
  CHECK(water.name == "water");
  CHECK(water.is_fluid());
  CHECK(gate.type == "elastic");
  CHECK(gate.is_solid());
  CHECK(water.first == 0);
  CHECK(gate.first == water.count);
  CHECK(water.count == 30 * 40);  // 0.15 x 0.2 m at 5 mm
  CHECK(gate.count == 4 * 27);    // 12 x 80 mm at 3 mm
  CHECK(water.density == 1000.0);
  CHECK(gate.spacing.x() == Approx(0.003));
  CHECK(run.particle_count() == water.count + gate.count);
  CHECK(run.particle_bodies()[0] == 0);
  CHECK(run.particle_bodies().back() == 1);

  CHECK(run.grid().cells == std::array<int, 2>{60, 30});
  CHECK(run.grid().extent_max.x() == Approx(0.6));
  CHECK(run.grid().extent_max.y() == Approx(0.3));
  CHECK(run.reference().length == 0.2);
  CHECK(run.reference().density == 1000.0);

  // Frame 2: the column sheared by a = 0.12 m at its base; hydrostatic pressure; the gate's
  // tip displaced by 8 mm (cantilever shape).
  const auto x = run.position(2);
  const auto d = run.displacement(2);
  const auto p = run.pressure(2);
  const auto v = run.volume(2);
  const auto s = run.stress(2);
  REQUIRE(x.size() == run.particle_count());
  CHECK(x[0].x() == Approx(0.0025 + 0.12 * (1.0 - 0.0025 / 0.2)));
  CHECK(p[0] == Approx(1000.0 * 9.81 * (0.2 - 0.0025)));
  CHECK(v[0] == Approx(0.005 * 0.005));
  CHECK(s[0] == StressComponents{0.0, 0.0, 0.0});
  const std::size_t tip = run.particle_count() - 1;  // top of the gate's last column
  const double rel = 0.0795 / 0.08;  // the top row of particles, 26.5 spacings up
  CHECK(d[tip].x() == Approx(0.008 * rel * rel * (3.0 - rel) / 2.0));
  CHECK(run.velocity(0)[0].norm() == 0.0);
  CHECK(run.probe_names().empty());
  fs::remove_all(dir.parent_path());
}

TEST_CASE("RunReader errors name the file and what is wrong", "[render][reader]") {
  const fs::path dir = temp_dir("errors");
  const std::string missing = (dir / "nothing.h5").string();
  try {
    RunReader r(missing);
    FAIL("no error for a missing file");
  } catch (const IoError& e) {
    CHECK(std::string(e.what()) == missing + ": no such file");
  }

  const std::string text = (dir / "text.h5").string();
  { std::ofstream(text) << "not hdf5\n"; }
  CHECK_THROWS_WITH(RunReader(text), Catch::Contains(text) && Catch::Contains("not an HDF5 file"));

  const std::string other = (dir / "other.h5").string();
  { h5::Handle f = h5::create_file(other); }
  CHECK_THROWS_WITH(RunReader(other), Catch::StartsWith(other + ": not a bsmpm run file"));

  // A run whose frame lacks a dataset: the error names the file and the dataset.
  const std::string path = test::write_dam_break_run(dir / "run", false, 2);
  {
    h5::Handle f = h5::open_file(path, true);
    h5::Handle frame = h5::open_group(h5::open_group(f, "frames"), "000001");
    REQUIRE(H5Ldelete(frame, "volume", H5P_DEFAULT) >= 0);
  }
  const RunReader run(path);
  CHECK(run.volume(0).size() == run.particle_count());
  CHECK_THROWS_WITH(run.volume(1), Catch::StartsWith(path + ": ") && Catch::Contains("volume"));
  CHECK_THROWS_WITH(run.position(7), Catch::StartsWith(path + ": no frame 7"));
  CHECK_THROWS_WITH(run.probe("P_z30"), Catch::Contains(path) && Catch::Contains("no probe"));
  fs::remove_all(dir.parent_path());
}

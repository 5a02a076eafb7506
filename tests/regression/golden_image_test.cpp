// Golden images: small synthetic runs (particles placed by formula and written through the
// real RunWriter, so that the images change only when the renderer does) rendered by the
// program at 320x180 and compared with tests/regression/golden/*.png.
//
// Tolerance. On one machine the output is bit-identical (same Mesa, FreeType and binary),
// whatever the thread count: llvmpipe with LP_NUM_THREADS = 1, 2 and 4, and with 128-bit
// vectors (LP_NATIVE_VECTOR_WIDTH=128, as on a CPU without AVX), gave identical images.
// What may differ on another machine is the rasteriser (another Mesa version). Standing in
// for one, Mesa's other software rasteriser (GALLIUM_DRIVER=softpipe) differs from llvmpipe
// on these images by at most rms 4.3, 1.0 % of the pixels and SSIM 0.995: single pixels at
// the edges of splats, where the two break ties between equally near particles or round a
// splat's edge through a pixel centre differently. Hence rms <= 8, share <= 3 %,
// SSIM >= 0.985 (max is not limited: an edge pixel can go from white to a full colour).
// Real changes exceed it: splat scale 1 -> 1.6 gives rms 10.1, the next frame 29, another
// colour map 29, another colour range 32, the colour bars moved 75 (scale 1 -> 1.3, half a
// pixel more margin at this size, passes: rms 5.5). (Labels: a changed digit would pass;
// their text is tested in unit tests.)
//
// To regenerate after an intended change: scripts/regenerate_golden_images (sets
// BSMPM_UPDATE_GOLDEN=1, which makes this test write the images instead of comparing).
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "test_support.hpp"
#include "unit/render/synthetic_run.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

const char* kTolerance = "rms=8,share=0.03,ssim=0.985";

struct Golden {
  std::string name;      // tests/regression/golden/<name>.png
  bool gate;             // with the elastic gate
  std::string options;   // for bsmpm render
};

const std::vector<Golden> kGoldens = {
    {"dam_break_pressure", false, "--frames 2 --size 320x180"},
    {"gate_velocity_jet", true, "--frames 3 --size 320x180 --field velocity --colormap jet --colorbar right"},
    {"gate_pstar_grid", true, "--layout 2x2 --size 320x180 --field pstar --solid-colormap viridis"},
};

int run(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
  REQUIRE(WIFEXITED(status));
  return WEXITSTATUS(status);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("Rendered frames match the golden images", "[render][golden]") {
  const fs::path dir = test::scratch_dir("golden");
  const fs::path golden_dir = BSMPM_GOLDEN_DIR;
  const bool update = std::getenv("BSMPM_UPDATE_GOLDEN") != nullptr;
  const std::string program = BSMPM_EXECUTABLE;
  for (const Golden& g : kGoldens) {
    INFO("golden image " << g.name);
    const std::string run_file = test::write_dam_break_run(dir / g.name, g.gate, 4);
    const fs::path rendered = dir / (g.name + ".png");
    const fs::path log = dir / (g.name + ".log");
    REQUIRE(run(program + " render " + run_file + " " + g.options + " --quiet --out " + rendered.string(), log) == 0);
    const fs::path golden = golden_dir / (g.name + ".png");
    if (update) {
      fs::copy_file(rendered, golden, fs::copy_options::overwrite_existing);
      WARN("wrote " << golden.string());
      continue;
    }
    REQUIRE(fs::exists(golden));
    const fs::path diff = dir / (g.name + ".diff.png");
    const int status = run(program + " compare " + golden.string() + " " + rendered.string() + " --tolerance " +
                               kTolerance + " --diff " + diff.string(),
                           log);
    INFO(read_text(log) << "rendered: " << rendered.string() << "\ndifference: " << diff.string());
    CHECK(status == 0);
    if (status == 0) fs::remove_all(dir / g.name);
  }
  // Keep what failed for inspection.
  bool failed = false;
  for (const Golden& g : kGoldens) failed = failed || (!update && fs::exists(dir / g.name));
  if (!failed) fs::remove_all(dir);
}

// The golden images of the rendering regression test (tests/regression/golden/*.png): small
// synthetic runs (particles placed by formula and written through the real RunWriter, so
// that the images change only when the renderer does) rendered by the program at 320x180.
// Shared by the test, which compares, and by the update_golden_images target, which writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "unit/render/synthetic_run.hpp"

namespace bsmpm::test {

struct Golden {
  std::string name;     // tests/regression/golden/<name>.png
  bool gate;            // with the elastic gate
  std::string options;  // for bsmpm render
};

inline const std::vector<Golden>& goldens() {
  static const std::vector<Golden> all = {
      {"dam_break_pressure", false, "--frames 2 --size 320x180"},
      {"gate_velocity_jet", true, "--frames 3 --size 320x180 --field velocity --colormap jet --colorbar right"},
      {"gate_pstar_grid", true, "--layout 2x2 --size 320x180 --field pstar --solid-colormap viridis"},
  };
  return all;
}

struct RenderedGolden {
  std::string run_file;         // the synthetic run it was rendered from
  std::filesystem::path image;  // dir/<name>.png
  std::filesystem::path log;    // the program's output
  int status = -1;              // exit status of bsmpm render
};

// Writes the golden's synthetic run under `dir` and renders it with the program.
inline RenderedGolden render_golden(const Golden& g, const std::filesystem::path& dir) {
  RenderedGolden r;
  r.run_file = write_dam_break_run(dir / g.name, g.gate, 4);
  r.image = dir / (g.name + ".png");
  r.log = dir / (g.name + ".log");
  r.status = run_program("render " + r.run_file + " " + g.options + " --quiet --out " + r.image.string(), r.log).status;
  return r;
}

}  // namespace bsmpm::test

// A table of broken scenes: each must fail with its message, naming the file, line, column
// and key; the command-line program must exit non-zero and create no output.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

// A valid scene, line by line; each case replaces or appends lines.
const std::vector<std::string> kValid = {
    "[domain]",                                                          // 1
    "min = [0.0, 0.0]",                                                  // 2
    "max = [0.4, 0.2]",                                                  // 3
    "[grid]",                                                            // 4
    "cell_size = 0.01",                                                  // 5
    "order = 2",                                                         // 6
    "[time]",                                                            // 7
    "end = 0.01",                                                        // 8
    "cfl = 0.3",                                                         // 9
    "[materials.water]",                                                 // 10
    "type = \"fluid\"",                                                  // 11
    "density = 1000.0",                                                  // 12
    "bulk_modulus = 1.0e6",                                              // 13
    "equation_of_state = \"tait\"",                                      // 14
    "[[bodies]]",                                                        // 15
    "name = \"water\"",                                                  // 16
    "material = \"water\"",                                              // 17
    "shape = { type = \"rectangle\", min = [0.0, 0.0], max = [0.1, 0.1] }",  // 18
    "[[probes]]",                                                        // 19
    "name = \"p\"",                                                      // 20
    "type = \"wall_pressure\"",                                          // 21
    "wall = \"right\"",                                                  // 22
    "position = 0.05",                                                   // 23
};

struct BadCase {
  const char* what;
  std::vector<std::pair<int, std::string>> edits;  // line number (1-based) -> new text; 0 appends
  int line;                                        // where the error must point
  int column;                                      // 0: any column
  const char* key;
  const char* message;                             // regex the message must match
};

const std::vector<BadCase> kCases = {
    {"TOML syntax error", {{11, "type = \"fluid"}}, 11, 0, "", "TOML syntax error"},
    {"misspelt table", {{4, "[grids]"}}, 4, 2, "grids", "unknown key \\(did you mean 'grid'\\?\\)"},
    {"misspelt key", {{5, "cellsize = 0.01"}}, 5, 1, "grid.cellsize", "unknown key \\(did you mean 'cell_size'\\?\\)"},
    {"wrong type", {{5, "cell_size = \"1cm\""}}, 5, 13, "grid.cell_size", "expected a number, got a string"},
    {"negative cell size", {{5, "cell_size = -0.01"}}, 5, 13, "grid.cell_size", "must be > 0 \\(got -0.01\\)"},
    {"order out of range", {{6, "order = 4"}}, 6, 9, "grid.order", "must be in \\[1, 3\\] \\(got 4\\)"},
    {"integer expected", {{6, "order = 2.5"}}, 6, 9, "grid.order", "expected an integer, got a number"},
    {"grid too coarse", {{5, "cell_size = 0.1"}}, 5, 13, "grid.cell_size", "fewer than 4 cells"},
    {"missing table", {{7, "[timing]"}}, 1, 0, "time", "missing required key"},
    {"domain inverted", {{3, "max = [-0.4, 0.2]"}}, 3, 7, "domain.max", "must exceed domain.min"},
    {"vector of three", {{2, "min = [0.0, 0.0, 0.0]"}}, 2, 7, "domain.min", "expected an array of two numbers"},
    {"both time steps", {{0, ""}, {9, "cfl = 0.3\ndt = 1e-5"}}, 9, 7, "time.cfl", "either time.dt .* or time.cfl"},
    {"unknown material", {{17, "material = \"oil\""}}, 17, 12, "bodies[0].material", "no material \"oil\""},
    {"unknown model", {{11, "type = \"gas\""}}, 11, 8, "materials.water.type", "must be \"fluid\", \"incompressible_fluid\", \"elastic\" or \"rigid\""},
    {"bad equation of state", {{14, "equation_of_state = \"ideal\""}}, 14, 21, "materials.water.equation_of_state",
     "must be \"tait\" or \"linear\""},
    {"two stiffnesses", {{13, "bulk_modulus = 1.0e6\nsound_speed = 30.0"}}, 14, 15, "materials.water.sound_speed",
     "exactly one of bulk_modulus"},
    {"shape outside the domain", {{18, "shape = { type = \"rectangle\", min = [0.0, 0.0], max = [0.5, 0.1] }"}}, 18,
     18, "bodies[0].shape.type", "outside the domain"},
    {"rectangle inverted", {{18, "shape = { type = \"rectangle\", min = [0.1, 0.0], max = [0.0, 0.1] }"}}, 18, 55,
     "bodies[0].shape.max", "must exceed min"},
    {"duplicate body", {{0, "[[bodies]]\nname = \"water\"\nmaterial = \"water\"\nshape = { type = \"disk\", center = [0.3, 0.1], radius = 0.02 }"}},
     25, 8, "bodies[1].name", "already exists"},
    {"negative skin friction", {{3, "max = [0.4, 0.2]\nwalls = { skin_friction = -0.01 }"}}, 4, 27,
     "domain.walls.skin_friction", "must be >= 0 \\(got -0.01\\)"},
    {"probe on no wall", {{22, "wall = \"front\""}}, 22, 8, "probes[0].wall", "must be \"left\", \"right\", \"bottom\" or \"top\""},
    {"probe off the wall", {{23, "position = 0.5"}}, 23, 12, "probes[0].position", "must be in \\[0, 0.2\\]"},
    {"probe file name", {{20, "name = \"a/b\""}}, 20, 8, "probes[0].name", "letters, digits"},
    {"reaction sensor with a depth", {{21, "type = \"wall_reaction\"\ndepth = 0.002"}}, 22, 1, "probes[0].depth",
     "unknown key"},
    {"hydrostatic solid",
     {{11, "type = \"elastic\""}, {13, "youngs_modulus = 1e6"}, {14, ""},
      {18, "shape = { type = \"rectangle\", min = [0.0, 0.0], max = [0.1, 0.1] }\ninitial_stress = \"hydrostatic\""}},
     19, 18, "bodies[0].initial_stress", "applies to fluid bodies only"},
    {"hydrostatic without gravity",
     {{18, "shape = { type = \"rectangle\", min = [0.0, 0.0], max = [0.1, 0.1] }\ninitial_stress = \"hydrostatic\""},
      {0, "[gravity]\ng = 0.0"}},
     19, 18, "bodies[0].initial_stress", "needs gravity"},
    {"velocity of a rigid body",
     {{0, "[materials.steel]\ntype = \"rigid\"\n[[bodies]]\nname = \"wall\"\nmaterial = \"steel\"\n"
          "shape = { type = \"rectangle\", min = [0.3, 0.0], max = [0.35, 0.1] }\nvelocity = [1.0, 0.0]"}},
     30, 12, "bodies[1].velocity", "moves at its material's velocity"},
    {"rigid body without contact",
     {{0, "[materials.steel]\ntype = \"rigid\"\n[[bodies]]\nname = \"wall\"\nmaterial = \"steel\"\n"
          "shape = { type = \"rectangle\", min = [0.3, 0.0], max = [0.35, 0.1] }"}},
     26, 0, "bodies[1].material", "acts only through contact"},
    {"clamp away from its body",
     {{11, "type = \"elastic\""}, {13, "youngs_modulus = 1e6"}, {14, ""},
      {18, "shape = { type = \"rectangle\", min = [0.0, 0.0], max = [0.1, 0.1] }\n"
           "clamp = [{ min = [0.3, 0.0], max = [0.35, 0.0] }]"}},
     19, 0, "bodies[0].clamp[0].min", "does not touch its body"},
    // The incompressible fluid (method.md §12): its own keys, its table, what it cannot share a scene with.
    {"incompressible fluid with a bulk modulus", {{11, "type = \"incompressible_fluid\""}, {14, ""}}, 13, 1,
     "materials.water.bulk_modulus", "unknown key"},
    {"pressure table without an incompressible fluid", {{0, "[solver.pressure]\ntolerance = 1e-6"}}, 24, 0,
     "solver.pressure", "applies to an incompressible fluid"},
    {"pressure tolerance out of range",
     {{11, "type = \"incompressible_fluid\""}, {13, ""}, {14, ""}, {0, "[solver.pressure]\ntolerance = 0.5"}}, 25, 13,
     "solver.pressure.tolerance", "must be in \\(0, 0.1\\]"},
    {"pressure iterations out of range",
     {{11, "type = \"incompressible_fluid\""}, {13, ""}, {14, ""}, {0, "[solver.pressure]\nmax_iterations = 0"}}, 25,
     18, "solver.pressure.max_iterations", "must be in \\[1, 100000\\]"},
    {"pressure volume correction filter out of range",
     {{11, "type = \"incompressible_fluid\""}, {13, ""}, {14, ""}, {0, "[solver.pressure]\nvolume_correction_filter = 17"}},
     25, 28, "solver.pressure.volume_correction_filter", "must be in \\[0, 16\\]"},
    {"pressure volume measure unknown",
     {{11, "type = \"incompressible_fluid\""}, {13, ""}, {14, ""}, {0, "[solver.pressure]\nvolume_measure = \"count\""}},
     25, 18, "solver.pressure.volume_measure", "must be \"increment\" or \"fill\""},
    {"unknown pressure preconditioner",
     {{11, "type = \"incompressible_fluid\""}, {13, ""}, {14, ""}, {0, "[solver.pressure]\npreconditioner = \"ilu\""}},
     25, 18, "solver.pressure.preconditioner", "must be \"incomplete_cholesky\" or \"multigrid\""},
    {"elastic body beside incompressible water",
     {{11, "type = \"incompressible_fluid\""}, {13, ""}, {14, ""},
      {0, "[materials.rubber]\ntype = \"elastic\"\ndensity = 1100.0\nyoungs_modulus = 1e6\n[[bodies]]\nname = \"gate\"\n"
          "material = \"rubber\"\nshape = { type = \"rectangle\", min = [0.3, 0.0], max = [0.31, 0.1] }"}},
     30, 12, "bodies[1].material", "elastic body cannot share a scene with an incompressible fluid"},
    {"smoothed-volume readback without the smoothed volume", {{0, "[solver]\nsmoothed_volume_readback = \"values\""}},
     25, 0, "solver.smoothed_volume_readback", "applies only with fluid_volume = \"smoothed\""},
    {"smoothed-volume basis without the smoothed volume", {{0, "[solver]\nsmoothed_volume_basis = \"linear\""}},
     25, 0, "solver.smoothed_volume_basis", "applies only with fluid_volume = \"smoothed\""},
    {"unknown smoothed-volume basis",
     {{0, "[solver]\nfluid_volume = \"smoothed\"\nsmoothed_volume_basis = \"quadratic\""}}, 26, 25,
     "solver.smoothed_volume_basis", "must be \"velocity\", \"linear\" or \"linear_patches\""},
    {"sub-cell shifting out of range", {{0, "[solver]\nsubcell_shifting = 0.5"}}, 25, 20, "solver.subcell_shifting",
     "must be in \\[0, 0.25\\]"},
    {"shifting velocity without shifting", {{0, "[solver]\nvelocity_update = \"apic\"\nshifting_velocity = \"affine\""}},
     26, 0, "solver.shifting_velocity", "applies only with particle_shifting or subcell_shifting > 0"},
    {"shifting velocity with FLIP", {{0, "[solver]\nparticle_shifting = 0.05\nshifting_velocity = \"kept\""}}, 26, 0,
     "solver.shifting_velocity", "applies only with velocity_update = \"apic\""},
    {"unknown shifting velocity",
     {{0, "[solver]\nvelocity_update = \"apic\"\nparticle_shifting = 0.05\nshifting_velocity = \"taylor\""}}, 27, 21,
     "solver.shifting_velocity", "must be \"kept\" or \"affine\""},
    {"material point off its body",
     {{0, "[[probes]]\nname = \"tip\"\ntype = \"material_point\"\nbody = \"water\"\npoint = [0.3, 0.15]"}},
     28, 9, "probes[1].point", "more than a grid cell away"},
};

std::string scene_text(const BadCase& c) {
  std::vector<std::string> lines = kValid;
  std::vector<std::string> appended;
  for (const auto& [line, text] : c.edits) {
    if (line == 0) {
      if (!text.empty()) appended.push_back(text);
    } else {
      lines[line - 1] = text;
    }
  }
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  for (const auto& a : appended) s += a + "\n";
  return s;
}

fs::path temp_dir() { return test::scratch_dir("bad_scenes"); }

}  // namespace

TEST_CASE("The valid base scene loads", "[scene]") {
  std::string s;
  for (const auto& l : kValid) s += l + "\n";
  const auto scene = load_scene_text(s, "base.toml");
  CHECK(scene.bodies.size() == 1);
  CHECK(scene.probes.size() == 1);
}

TEST_CASE("Broken scenes fail with file:line:column, key and message", "[scene]") {
  const fs::path dir = temp_dir();
  for (std::size_t k = 0; k < kCases.size(); ++k) {
    const BadCase& c = kCases[k];
    const fs::path file = dir / ("case" + std::to_string(k) + ".toml");
    {
      std::ofstream out(file);
      out << scene_text(c);
    }
    INFO("case '" << c.what << "':\n" << scene_text(c));
    try {
      (void)load_scene(file.string());
      FAIL("no error");
    } catch (const SceneError& e) {
      INFO("got: " << e.what());
      CHECK(e.where().file == file.string());
      if (c.line > 0) CHECK(e.where().line == c.line);
      if (c.column > 0) CHECK(e.where().column == c.column);
      if (*c.key) CHECK(e.key() == c.key);
      CHECK(std::regex_search(e.message(), std::regex(c.message)));
      // what() is "file:line:column: key: message".
      CHECK(std::string(e.what()).rfind(file.string() + ":" + std::to_string(e.where().line) + ":", 0) == 0);
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("The program exits non-zero on a bad scene and writes nothing", "[scene][cli]") {
  const fs::path dir = temp_dir();
  for (std::size_t k : {std::size_t(2), std::size_t(12), std::size_t(16)}) {
    const BadCase& c = kCases[k];
    const fs::path file = dir / ("cli" + std::to_string(k) + ".toml");
    {
      std::ofstream out(file);
      out << scene_text(c);
    }
    const fs::path out_dir = dir / ("out" + std::to_string(k));
    const fs::path log = dir / "stderr.txt";
    const std::string cmd = std::string(BSMPM_EXECUTABLE) + " run " + file.string() + " --out " + out_dir.string() +
                            " > /dev/null 2> " + log.string();
    const int status = std::system(cmd.c_str());
    INFO("case '" << c.what << "'");
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 2);
    CHECK_FALSE(fs::exists(out_dir));
    std::ifstream in(log);
    const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(err.find(file.string() + ":" + std::to_string(c.line) + ":") != std::string::npos);
    CHECK(err.find(c.key) != std::string::npos);
  }
  fs::remove_all(dir);
}

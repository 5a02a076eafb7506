// Study files: what a valid one expands to, and that every mistake is an error naming the
// study file's line and column (scene keys that do not exist included) before anything runs.
#include <catch2/catch.hpp>

#include <string>

#include "core/error.hpp"
#include "study/study_cases.hpp"
#include "study/study_loader.hpp"
#include "study/study_options.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Study text as if it stood in tests/study/ (its scene path is relative to that folder).
const std::string kPath = test::source_path("tests/study/inline_study.toml");

const std::string kHeader =
    "[study]\n"                                              // 1
    "name = \"s\"\n"                                         // 2
    "scene = \"../../scenes/lobovsky_h300.toml\"\n"          // 3
    "set = { \"grid.cell_size\" = 0.02 }\n";                 // 4

const std::string kAxis =
    "[[axes]]\n"                                             // 5
    "name = \"grid\"\n"                                      // 6
    "key = \"grid.cell_size\"\n"                             // 7
    "values = [0.025, 0.02]\n";                              // 8

// The error loading and validating `text` gives, or "" when there is none.
SceneError study_error(const std::string& text) {
  try {
    const StudyDescription s = load_study_text(text, kPath);
    validate_cases(s, expand_cases(s, "v1"));
  } catch (const SceneError& e) {
    return e;
  }
  FAIL("the study was accepted");
  throw;
}

}  // namespace

TEST_CASE("the tiny study expands to four keyed cases, the last axis fastest", "[study]") {
  const StudyDescription s = load_study(test::source_path("tests/study/tiny_study.toml"));
  REQUIRE(s.axes.size() == 2);
  CHECK(s.axes[0].values[1].label == "300 mm");
  CHECK(s.axes[0].values[1].coordinate == 0.3);
  CHECK(s.axes[1].values[0].assignments[0].text() == "grid.cell_size=0.025");
  const auto cases = expand_cases(s, "bsmpm 1");
  REQUIRE(cases.size() == 4);
  CHECK(cases[1].value_index == std::vector<std::size_t>{0, 1});
  CHECK(cases[2].value_index == std::vector<std::size_t>{1, 0});
  // The defaults first, then one axis after the other; TOML values written back exactly.
  const auto o = cases[3].overrides();
  REQUIRE(o.size() == 6);
  CHECK(o[0] == "output.frame_interval=0.2");
  CHECK(o[3] == "bodies[0].shape.max=[0.6, 0.3]");
  CHECK(o[5] == "grid.cell_size=0.02");
  validate_cases(s, cases);
  // Keys: distinct, stable, and new for another scene text or program version.
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t j = i + 1; j < cases.size(); ++j) CHECK(cases[i].key != cases[j].key);
  CHECK(expand_cases(s, "bsmpm 1")[2].key == cases[2].key);
  CHECK(expand_cases(s, "bsmpm 2")[2].key != cases[2].key);
  StudyDescription edited = s;
  edited.scene_text += "\n# a comment\n";
  CHECK(expand_cases(edited, "bsmpm 1")[2].key != cases[2].key);
  CHECK(describe_case(s, cases[2]) == "H = 300 mm, grid = 0.025");
}

TEST_CASE("unknown keys in a study file are errors at their line and column", "[study][errors]") {
  SECTION("in [study]") {
    const SceneError e = study_error(kHeader + "treads = 2\n" + kAxis);
    CHECK(e.where().line == 5);
    CHECK(e.where().column == 1);
    CHECK(e.key() == "study.treads");
    CHECK(e.message().find("unknown key (did you mean 'threads'?)") != std::string::npos);
  }
  SECTION("in an axis") {
    const SceneError e = study_error(kHeader + kAxis + "units = \"m\"\n");
    CHECK(e.where().line == 9);
    CHECK(e.key() == "axes[0].units");
  }
  SECTION("in a metric") {
    const SceneError e = study_error(kHeader + kAxis + "[[metrics]]\nname = \"p\"\ntype = \"peak\"\nprobe = \"P_z30\"\nwindow_star = [0, 4]\n");
    CHECK(e.where().line == 13);
    CHECK(e.key() == "metrics[0].window_star");
  }
  SECTION("at the top") {
    const SceneError e = study_error(kHeader + kAxis + "[plot]\nname = \"x\"\n");
    CHECK(e.where().line == 9);
    CHECK(e.key() == "plot");
  }
}

TEST_CASE("an axis without values, or no axis at all, is an error", "[study][errors]") {
  const SceneError e = study_error(kHeader + "[[axes]]\nname = \"grid\"\nkey = \"grid.cell_size\"\nvalues = []\n");
  CHECK(e.where().line == 8);
  CHECK(e.where().column == 10);
  CHECK(e.message() == "an axis needs at least one value");
  CHECK(study_error(kHeader).message().find("at least one [[axes]]") != std::string::npos);
}

TEST_CASE("an axis naming a key the scene does not have is an error at that value's line", "[study][errors]") {
  SECTION("a misspelt key of a keyed axis: the error names the value that set it") {
    const SceneError e = study_error(kHeader + "[[axes]]\nname = \"g\"\nkey = \"grid.cell_sise\"\nvalues = [0.025,\n  0.02]\n");
    CHECK(e.where().file == kPath);
    CHECK(e.where().line == 8);  // the first case's value
    CHECK(e.where().column == 11);
    CHECK(e.key() == "grid.cell_sise");
    CHECK(e.message().find("unknown key (did you mean 'cell_size'?)") != std::string::npos);
  }
  SECTION("a key inside a table value") {
    const SceneError e = study_error(kHeader +
                                     "[[axes]]\nname = \"H\"\nvalues = [\n"
                                     "  { value = 0.3, set = { \"bodies[0].shape.max\" = [0.6, 0.3] } },\n"
                                     "  { value = 0.6, set = { \"reference.lenght\" = 0.6 } },\n]\n");
    CHECK(e.where().line == 9);
    CHECK(e.where().column == 47);
    CHECK(e.message().find("unknown key") != std::string::npos);
  }
  SECTION("an element past the end of an array") {
    const SceneError e = study_error(kHeader + "[[axes]]\nname = \"v\"\nkey = \"bodies[1].velocity\"\nvalues = [[1.0, 0.0]]\n");
    CHECK(e.where().line == 8);
    CHECK(e.message().find("past the end") != std::string::npos);
  }
  SECTION("a value out of the scene's range") {
    const SceneError e = study_error(kHeader + "[[axes]]\nname = \"o\"\nkey = \"grid.order\"\nvalues = [2, 7]\n");
    CHECK(e.where().line == 8);
    CHECK(e.where().column == 14);
    CHECK(e.message().find("must be in [1, 3]") != std::string::npos);
  }
}

TEST_CASE("metrics and plots must name probes, columns and metrics that exist", "[study][errors]") {
  const std::string metric = "[[metrics]]\nname = \"p\"\ntype = \"peak\"\n";
  SECTION("an unknown probe") {
    const SceneError e = study_error(kHeader + kAxis + metric + "probe = \"P_z31\"\n");
    CHECK(e.where().line == 12);
    CHECK(e.message().find("no probe \"P_z31\"") != std::string::npos);
    CHECK(e.message().find("P_z30, P_z80") != std::string::npos);
  }
  SECTION("an unknown column") {
    const SceneError e = study_error(kHeader + kAxis + metric + "probe = \"P_z30\"\ncolumn = \"dx\"\n");
    CHECK(e.message().find("no column \"dx\"") != std::string::npos);
  }
  SECTION("an unknown metric type") {
    const SceneError e = study_error(kHeader + kAxis + "[[metrics]]\nname = \"p\"\ntype = \"peek\"\n");
    CHECK(e.where().line == 11);
    CHECK(e.message().find("\"peak\"") != std::string::npos);
  }
  SECTION("a plot of an unknown metric") {
    const SceneError e = study_error(kHeader + kAxis + metric + "probe = \"P_z30\"\n[[plots]]\nname = \"f\"\nx = \"grid\"\ny = \"q\"\n");
    CHECK(e.where().line == 16);
    CHECK(e.message().find("no metric \"q\"") != std::string::npos);
  }
  SECTION("a plot against an unknown axis") {
    const SceneError e = study_error(kHeader + kAxis + metric + "probe = \"P_z30\"\n[[plots]]\nname = \"f\"\nx = \"H\"\ny = \"p\"\n");
    CHECK(e.message().find("no axis named \"H\"") != std::string::npos);
  }
}

TEST_CASE("an axis value may set nothing (the base scene), the study's own set may not", "[study]") {
  const std::string axis =
      "[[axes]]\nname = \"setting\"\nvalues = [{ value = 0, label = \"shipped\", set = {} },\n"
      "  { value = 1, label = \"order 3\", set = { \"grid.order\" = 3 } }]\n";
  const StudyDescription s = load_study_text(kHeader + axis, kPath);
  const auto cases = expand_cases(s, "v1");
  REQUIRE(cases.size() == 2);
  CHECK(cases[0].overrides() == std::vector<std::string>{"grid.cell_size=0.02"});  // the study's set only
  CHECK(cases[1].overrides().back() == "grid.order=3");
  CHECK(cases[0].key != cases[1].key);
  validate_cases(s, cases);
  const std::string empty_study_set = "[study]\nname = \"s\"\nscene = \"../../scenes/lobovsky_h300.toml\"\nset = {}\n";
  const SceneError e = study_error(empty_study_set + kAxis);
  CHECK(e.where().line == 4);
  CHECK(e.message() == "sets no scene key");
}

TEST_CASE("An axis of tables is narrowed by its labels (--axis), an unknown label names those it has", "[study][errors]") {
  const std::string axis =
      "[[axes]]\nname = \"setting\"\nvalues = [{ value = 0, label = \"shipped\", set = {} },\n"
      "  { value = 1, label = \"order 3\", set = { \"grid.order\" = 3 } },\n"
      "  { value = 2, label = \"FLIP 0.95\", set = { \"solver.flip\" = 0.95 } }]\n";
  StudyDescription s = load_study_text(kHeader + axis, kPath);
  const auto all = expand_cases(s, "v1");
  apply_study_options(s, {}, {"setting=FLIP 0.95,shipped"});
  REQUIRE(s.axes[0].values.size() == 2);
  CHECK(s.axes[0].values[0].label == "FLIP 0.95");
  CHECK(s.axes[0].values[1].label == "shipped");
  const auto narrowed = expand_cases(s, "v1");
  REQUIRE(narrowed.size() == 2);
  CHECK(narrowed[0].key == all[2].key);  // a value chosen by label keeps its case (and its results)
  CHECK(narrowed[1].key == all[0].key);
  try {
    apply_study_options(s, {}, {"setting=APIC"});
    FAIL("an unknown label was accepted");
  } catch (const UsageError& e) {
    CHECK(std::string(e.what()).find("no value labelled \"APIC\"") != std::string::npos);
    CHECK(std::string(e.what()).find("\"FLIP 0.95\", \"shipped\"") != std::string::npos);
  }
}

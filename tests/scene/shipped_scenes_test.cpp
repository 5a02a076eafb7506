// Every scene in scenes/ validates (including its [render] table) and builds.
#include <catch2/catch.hpp>

#include <filesystem>

#include "settings/render_options.hpp"
#include "test_support.hpp"

using namespace bsmpm;

TEST_CASE("Every shipped scene validates and builds", "[scene]") {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("scenes"))) {
    if (entry.path().extension() != ".toml") continue;
    INFO(entry.path().string());
    const SceneDescription scene = load_scene(entry.path().string(), {}, {render::render_scene_extension()});
    const auto sim = build_simulation(scene);
    CHECK(sim->particles().size() > 0);
    CHECK(!sim->describe_effects().empty());
    ++count;
  }
  CHECK(count >= 9);
}

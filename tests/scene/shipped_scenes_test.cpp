// Every scene in scenes/ validates (including its [render] table), builds with the particles
// its shapes ask for, and takes its first steps soundly.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "settings/render_options.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

// Particles a shape should receive on the lattice of spacing s: a rectangle is filled by
// round(width / s) x round(height / s) particles; other shapes take the lattice points inside
// them, area / (sx sy) up to one row of lattice cells along the boundary.
void check_seeding(const BodyDescription& desc, const Body& body, const Vec2& s) {
  INFO("body " << desc.name);
  const double n = static_cast<double>(body.size());
  if (const auto* r = std::get_if<Rectangle>(&desc.shape)) {
    const Vec2 size = r->max - r->min;
    CHECK(n == std::round(size.x() / s.x()) * std::round(size.y() / s.y()));
  } else {
    const Rectangle box = bounding_box(desc.shape);
    const double boundary_cells = 2.0 * ((box.max - box.min).x() / s.x() + (box.max - box.min).y() / s.y());
    CHECK(std::abs(n - area(desc.shape) / (s.x() * s.y())) <= boundary_cells);
  }
}

}  // namespace

TEST_CASE("Every shipped scene builds as seeded and takes five sound steps", "[scene]") {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("scenes"))) {
    if (entry.path().extension() != ".toml") continue;
    INFO(entry.path().string());
    const SceneDescription scene = load_scene(entry.path().string(), {}, {render::render_scene_extension()});
    const auto sim = build_simulation(scene);
    REQUIRE(sim->bodies().size() == scene.bodies.size());
    const Vec2 spacing = scene.actual_cell_size() / scene.particles_per_cell;
    std::size_t seeded = 0;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      check_seeding(scene.bodies[b], sim->bodies()[b], spacing);
      seeded += sim->bodies()[b].size();
    }
    REQUIRE(sim->particles().size() == seeded);
    const std::vector<Body> bodies_at_start = sim->bodies();

    const GridInfo g = sim->grid_info();
    const double h_min = std::min(g.cell_size.x(), g.cell_size.y());
    for (int k = 0; k < 5; ++k) sim->advance(time_step(scene.time, sim->max_signal_speed(), h_min));

    // No particle lost or moved to another body, none pushed back into the tank, every
    // state finite and no particle inverted.
    CHECK(sim->particles().size() == seeded);
    for (std::size_t b = 0; b < bodies_at_start.size(); ++b) {
      CHECK(sim->bodies()[b].begin == bodies_at_start[b].begin);
      CHECK(sim->bodies()[b].end == bodies_at_start[b].end);
    }
    CHECK(sim->stats().clamped_positions == 0);
    const Particles& ps = sim->particles();
    std::size_t bad = 0;
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (!ps.x[p].allFinite() || !ps.v[p].allFinite() || !ps.stress[p].allFinite() || !ps.F[p].allFinite() ||
          !(ps.J[p] > 0.0) || !std::isfinite(ps.pressure[p]))
        ++bad;
    CHECK(bad == 0);
    ++count;
  }
  CHECK(count >= 9);
}

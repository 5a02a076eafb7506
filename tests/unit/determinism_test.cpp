// Same scene, same binary -> same bits, whatever the thread count.
#include <catch2/catch.hpp>

#include <omp.h>

#include <cstring>

#include "test_support.hpp"

using namespace bsmpm;

namespace {
std::vector<double> state_after(int threads, long steps) {
  omp_set_num_threads(threads);
  // About 9,000 particles: large enough that every parallel loop runs in parallel.
  const SceneDescription scene =
      load_scene(test::scene_path("martin_moyce.toml"), {"grid.cell_size=0.0017859", "solver.sort_interval=7"});
  auto sim = build_simulation(scene);
  REQUIRE(sim->particles().size() > 8000);
  for (long k = 0; k < steps; ++k) sim->advance(2e-5);
  const Particles& ps = sim->particles();
  std::vector<double> out;
  for (std::size_t id = 0; id < ps.size(); ++id) {
    const std::size_t p = sim->index_of_id()[id];
    out.insert(out.end(), {ps.x[p].x(), ps.x[p].y(), ps.v[p].x(), ps.v[p].y(), ps.J[p], ps.pressure[p]});
  }
  return out;
}
}  // namespace

TEST_CASE("Results are bit-identical for 1, 2 and 3 threads", "[determinism]") {
  const int saved = omp_get_max_threads();
  const auto one = state_after(1, 300);
  const auto two = state_after(2, 300);
  const auto three = state_after(3, 300);
  omp_set_num_threads(saved);
  REQUIRE(one.size() == two.size());
  CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(one.data(), three.data(), one.size() * sizeof(double)) == 0);
}

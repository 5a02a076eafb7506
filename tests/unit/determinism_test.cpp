// Same scene, same binary -> same bits, whatever the thread count: in process for a fluid
// scene, and through `bsmpm run --threads N` for the scenes with contact, rigid bodies and
// clamps, comparing the particle data of the run files bit for bit.
#include <catch2/catch.hpp>

#include <omp.h>

#include <cstring>
#include <fstream>
#include <map>

#include "io/hdf5.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {
// Positions, velocities, J and pressure of every particle (in id order) after `steps` steps
// of `dt` on `threads` threads of scenes/NAME at a 1.79 mm grid (re-sorted every 7 steps);
// the scene must hold more than `min_particles` particles, an incompressible one more than
// `min_unknowns` pressure unknowns at the end.
std::vector<double> state_after(const std::string& name, std::size_t min_particles, int threads, long steps,
                                double dt, std::vector<std::string> overrides, int min_unknowns = 1000) {
  omp_set_num_threads(threads);
  overrides.insert(overrides.begin(), {"grid.cell_size=0.0017859", "solver.sort_interval=7"});
  const SceneDescription scene = load_scene(test::scene_path(name), overrides);
  auto sim = build_simulation(scene);
  REQUIRE(sim->particles().size() > min_particles);
  for (long k = 0; k < steps; ++k) sim->advance(dt);
  if (is_incompressible(scene.bodies.front().material)) REQUIRE(sim->last_step().pressure.unknowns > min_unknowns);
  const Particles& ps = sim->particles();
  std::vector<double> out;
  for (std::size_t id = 0; id < ps.size(); ++id) {
    const std::size_t p = sim->index_of_id()[id];
    out.insert(out.end(), {ps.x[p].x(), ps.x[p].y(), ps.v[p].x(), ps.v[p].y(), ps.J[p], ps.pressure[p]});
  }
  return out;
}

// Checks that 1, 2 and 3 threads leave the same bits (state_after).
void check_thread_counts_agree(const std::string& name, std::size_t min_particles, long steps, double dt,
                               const std::vector<std::string>& overrides = {}, int min_unknowns = 1000) {
  const int saved = omp_get_max_threads();
  const auto one = state_after(name, min_particles, 1, steps, dt, overrides, min_unknowns);
  const auto two = state_after(name, min_particles, 2, steps, dt, overrides, min_unknowns);
  const auto three = state_after(name, min_particles, 3, steps, dt, overrides, min_unknowns);
  omp_set_num_threads(saved);
  REQUIRE(one.size() == two.size());
  CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(one.data(), three.data(), one.size() * sizeof(double)) == 0);
}
}  // namespace

TEST_CASE("Results are bit-identical for 1, 2 and 3 threads", "[determinism]") {
  // About 9,000 particles: large enough that every parallel loop runs in parallel.
  check_thread_counts_agree("martin_moyce.toml", 8000, 300, 2e-5);
}

TEST_CASE("The J fits on the knots are bit-identical for 1, 2 and 3 threads", "[determinism]") {
  // solver.smoothed_volume_basis (method.md §4): the hats' and the cells' moments are
  // scattered in the strips' order, the cells carried to the knots row by row.
  for (const char* basis : {"\"linear\"", "\"linear_patches\""}) {
    INFO("smoothed_volume_basis = " << basis);
    check_thread_counts_agree("martin_moyce.toml", 8000, 100, 2e-5,
                              {std::string("solver.smoothed_volume_basis=") + basis});
  }
}

TEST_CASE("The incompressible fluid's results are bit-identical for 1, 2 and 3 threads", "[determinism]") {
  // The pressure projection (method.md §12) scatters D in the strips' order, gathers D^T per
  // control point and D per vertex, and Eigen's conjugate gradients sum their dot products
  // serially: the same bits for any thread count. About 8,000 particles, 40 steps of 0.5 ms.
  check_thread_counts_agree("martin_moyce_incompressible.toml", 7000, 40, 5e-4);
}

TEST_CASE("The incompressible fluid with J from the hats' fill is bit-identical for 1, 2 and 3 threads",
          "[determinism]") {
  // The fill (method.md §12, "The water's volume") is scattered in the strips' order too.
  check_thread_counts_agree("martin_moyce_incompressible.toml", 7000, 40, 5e-4,
                            {"solver.pressure.volume_measure=\"fill\"", "solver.pressure.volume_correction=0.1"});
}

TEST_CASE("The incompressible fluid's multigrid solve is bit-identical for 1, 2 and 3 threads", "[determinism]") {
  // The multigrid (method.md §12, "The solve"): the assembly, the Galerkin products and the
  // V-cycle's strips run side by side above 4,096 unknowns. The Lobovsky tank at 5 mm: about
  // 7,000 unknowns, 28,800 particles, 30 steps of 1 ms (the water falling, before the impact).
  check_thread_counts_agree("lobovsky_h300_incompressible.toml", 25000, 30, 1e-3, {"grid.cell_size=0.005"}, 4096);
}

TEST_CASE("Particle shifting with the sub-cell drift is bit-identical for 1, 2 and 3 threads", "[determinism]") {
  // The sub-cell volumes (method.md §10) are scattered in the strips' order like the grid's.
  const std::vector<std::string> on = {"solver.particle_shifting=0.05", "solver.subcell_shifting=0.01"};
  check_thread_counts_agree("martin_moyce.toml", 8000, 300, 2e-5, on);
  // ... and the drift acts within those steps (else the check above proves nothing about it).
  const int saved = omp_get_max_threads();
  const auto with = state_after("martin_moyce.toml", 8000, 2, 300, 2e-5, on);
  const auto without = state_after("martin_moyce.toml", 8000, 2, 300, 2e-5, {"solver.particle_shifting=0.05"});
  omp_set_num_threads(saved);
  CHECK(with != without);
}

namespace {

// Every dataset of every frame and every probe series of a run file, by path.
std::map<std::string, std::vector<double>> run_data(const std::filesystem::path& h5_path) {
  std::map<std::string, std::vector<double>> data;
  h5::Handle f = h5::open_file(h5_path.string());
  h5::Handle frames = h5::open_group(f, "frames");
  for (const auto& frame : h5::children(frames)) {
    h5::Handle g = h5::open_group(frames, frame);
    for (const auto& name : h5::children(g)) data["frames/" + frame + "/" + name] = h5::read_doubles(g, name);
  }
  if (h5::exists(f, "probes")) {
    h5::Handle probes = h5::open_group(f, "probes");
    for (const auto& name : h5::children(probes)) data["probes/" + name] = h5::read_doubles(probes, name);
  }
  return data;
}

// Runs `scene` with `overrides` on 1 and on 2 threads and compares the run files.
void check_bit_identical(const std::string& label, const std::filesystem::path& scene, const std::string& overrides) {
  std::map<int, std::map<std::string, std::vector<double>>> runs;
  for (int threads : {1, 2}) {
    const auto dir = test::scratch_dir(label + "_" + std::to_string(threads)) / "run";
    const auto r = test::run_program("run " + scene.string() + " --out " + dir.string() + " --quiet --threads " +
                                         std::to_string(threads) + " " + overrides,
                                     dir.string() + ".log");
    INFO(r.output);
    REQUIRE(r.status == 0);
    h5::Handle f = h5::open_file((dir / "run.h5").string());
    REQUIRE(h5::get_long_attribute(h5::open_group(f, "provenance"), "threads") == threads);
    runs[threads] = run_data(dir / "run.h5");
  }
  const auto& one = runs[1];
  const auto& two = runs[2];
  REQUIRE(one.size() == two.size());
  REQUIRE(one.size() > 10);  // frames x particle fields, and the probes
  for (const auto& [name, values] : one) {
    INFO(name);
    REQUIRE(two.count(name) == 1);
    REQUIRE(values.size() == two.at(name).size());
    CHECK(std::memcmp(values.data(), two.at(name).data(), values.size() * sizeof(double)) == 0);
  }
}

}  // namespace

TEST_CASE("bsmpm run: water against the clamped elastic gate is bit-identical on 1 and 2 threads",
          "[determinism][cli][contact]") {
  // scenes/elastic_gate.toml at 4 mm with the water column standing 2 mm from the gate, so
  // that the contact and the clamp act from the first steps; 30 ms.
  check_bit_identical("gate", test::scene_path("elastic_gate.toml"),
                      "--set grid.cell_size=0.004 --set time.dt=3e-5 --set time.end=0.03 "
                      "--set output.frame_interval=0.01 --set 'bodies[0].shape.min=[0.16, 0.0]' "
                      "--set 'bodies[0].shape.max=[0.29, 0.12]'");
}

TEST_CASE("bsmpm run: a rigid piston pushing water onto a clamped plate is bit-identical on 1 and 2 threads",
          "[determinism][cli][contact]") {
  const std::string scene = test::fixture_path("piston_water_plate.toml");
  check_bit_identical("piston", scene, "");
}

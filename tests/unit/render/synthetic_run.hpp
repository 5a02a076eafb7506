// Run files written by the tests themselves, through the real RunWriter, with particles
// the test places and moves by formula: rendering tests then depend on the renderer only,
// not on the solver (which changes as the physics does), and run in milliseconds.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/run_writer.hpp"
#include "step/simulation.hpp"

namespace bsmpm::test {

// A Simulation whose state the test sets; advance() only moves the clock.
class SyntheticSimulation final : public Simulation {
 public:
  explicit SyntheticSimulation(GridInfo grid) : grid_(grid) {}

  // Adds a body of particles at `positions`, each of volume `volume`; returns its index.
  BodyId add_body(const std::string& name, Material material, const std::vector<Vec2>& positions, double spacing) {
    Body b;
    b.name = name;
    b.material = material;
    b.begin = particles_.size();
    b.spacing = Vec2(spacing, spacing);
    const auto id = static_cast<BodyId>(bodies_.size());
    for (const Vec2& p : positions) {
      particles_.push_back(p, density_of(material) * spacing * spacing, spacing * spacing, id);
      index_of_id_.push_back(static_cast<std::uint32_t>(index_of_id_.size()));
    }
    b.end = particles_.size();
    bodies_.push_back(b);
    return id;
  }
  Particles& state() { return particles_; }

  void advance(double dt) override {
    time_ += dt;
    ++steps_;
  }
  double max_signal_speed() const override { return 0.0; }
  double time() const override { return time_; }
  long step_count() const override { return steps_; }
  const Particles& particles() const override { return particles_; }
  const std::vector<Body>& bodies() const override { return bodies_; }
  const std::vector<std::uint32_t>& index_of_id() const override { return index_of_id_; }
  GridInfo grid_info() const override { return grid_; }
  int layer_count() const override { return static_cast<int>(bodies_.size()); }
  const SimulationStats& stats() const override { return stats_; }
  const StepDiagnostics& last_step() const override { return diagnostics_; }
  std::vector<std::string> describe_effects() const override { return {}; }
  const std::vector<std::unique_ptr<Probe>>& probes() const override { return probes_; }
  void sample_probes() override {}

 private:
  GridInfo grid_;
  Particles particles_;
  std::vector<Body> bodies_;
  std::vector<std::uint32_t> index_of_id_;
  double time_ = 0.0;
  long steps_ = 0;
  SimulationStats stats_;
  StepDiagnostics diagnostics_;
  std::vector<std::unique_ptr<Probe>> probes_;
};

// Points of a lattice of spacing h filling the rectangle [lo, hi] (cell centres).
inline std::vector<Vec2> lattice(Vec2 lo, Vec2 hi, double h) {
  std::vector<Vec2> out;
  const int nx = static_cast<int>(std::lround((hi.x() - lo.x()) / h));
  const int ny = static_cast<int>(std::lround((hi.y() - lo.y()) / h));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) out.emplace_back(lo.x() + (i + 0.5) * h, lo.y() + (j + 0.5) * h);
  return out;
}

inline GridInfo tank_grid(double width, double height, double cell) {
  GridInfo g;
  g.order = 2;
  g.cell_size = Vec2(cell, cell);
  g.cells_x = static_cast<int>(std::lround(width / cell));
  g.cells_y = static_cast<int>(std::lround(height / cell));
  return g;
}

// Writes DIR/run.h5 with `frames` frames `dt` apart; `pose(sim, k)` sets the state of frame k.
inline std::string write_synthetic_run(const std::filesystem::path& dir, SyntheticSimulation& sim, int frames,
                                       double dt, const std::function<void(SyntheticSimulation&, int)>& pose,
                                       const std::string& effective_scene = "", const std::string& title = "synthetic") {
  std::filesystem::create_directories(dir);
  RunProvenance prov;
  prov.title = title;
  prov.scene_path = "synthetic";
  prov.effective_scene = effective_scene;
  prov.command_line = "test";
  prov.end_time = dt * (frames - 1);
  prov.reference.length = 0.2;
  prov.reference.density = 1000.0;
  prov.reference.gravity = 9.81;
  RunWriter writer(dir.string(), prov, sim);
  for (int k = 0; k < frames; ++k) {
    if (k > 0) sim.advance(dt);
    pose(sim, k);
    writer.write_frame(sim, dt);
  }
  writer.finish("completed", sim, dt);
  return writer.h5_path();
}

// A water column 0.15 m wide and 0.2 m high in a 0.6 x 0.3 m tank, sheared towards +x
// (x = X + a_k (1 - Y/H), area-preserving) with hydrostatic pressure; with `gate`, an
// elastic plate 12 x 80 mm at x = 0.3 m bending towards +x as a cantilever.
inline std::string write_dam_break_run(const std::filesystem::path& dir, bool gate, int frames = 4,
                                       const std::string& effective_scene = "") {
  SyntheticSimulation sim(tank_grid(0.6, 0.3, 0.01));
  const double h = 0.005, column = 0.2, rho = 1000.0, g = 9.81;
  sim.add_body("water", WeaklyCompressibleFluid{}, lattice({0.0, 0.0}, {0.15, column}, h), h);
  if (gate) sim.add_body("gate", ElasticSolid{}, lattice({0.3, 0.0}, {0.312, 0.08}, 0.003), 0.003);
  const double dt = 0.05;
  auto pose = [&](SyntheticSimulation& s, int k) {
    Particles& p = s.state();
    const auto& bodies = s.bodies();
    const double a = 0.06 * k;  // shear of the column at this frame
    for (std::size_t i = bodies[0].begin; i < bodies[0].end; ++i) {
      const Vec2 X = p.x0[i];
      p.x[i] = Vec2(X.x() + a * (1.0 - X.y() / column), X.y());
      p.v[i] = Vec2(k > 0 ? a / (k * dt) * (1.0 - X.y() / column) : 0.0, 0.0);
      p.pressure[i] = rho * g * (column - X.y());
    }
    if (bodies.size() > 1) {
      const double tip = 0.004 * k, length = 0.08;
      for (std::size_t i = bodies[1].begin; i < bodies[1].end; ++i) {
        const double s_rel = p.x0[i].y() / length;
        p.x[i] = p.x0[i] + Vec2(tip * s_rel * s_rel * (3.0 - s_rel) / 2.0, 0.0);
      }
    }
  };
  return write_synthetic_run(dir, sim, frames, dt, pose, effective_scene, gate ? "synthetic gate" : "synthetic dam break");
}

}  // namespace bsmpm::test

// The unit tests' smallest scene, built by hand: one body on one grid layer, and a simulation
// of it with no effects and no probes.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "step/bsmpm_simulation.hpp"

namespace bsmpm::test {

// A StepState on `grid` holding one body, `name` of `material`, whose particles `seed(particles)`
// pushes (initial spacing `spacing`), mapped to grid layer 0.
template <int P, class Seed>
StepState<P> one_body_state(const Grid<P>& grid, const std::string& name, Material material, const Vec2& spacing,
                            Seed&& seed) {
  StepState<P> st;
  st.grid = grid;
  Body body;
  body.name = name;
  body.material = std::move(material);
  seed(st.particles);
  body.end = st.particles.size();
  body.spacing = spacing;
  st.bodies.push_back(body);
  st.layers.resize(1);
  return st;
}

template <int P>
std::unique_ptr<BsmpmSimulation<P>> bare_simulation(StepState<P> st, const SolverSettings& settings) {
  return std::make_unique<BsmpmSimulation<P>>(std::move(st), settings, std::vector<std::unique_ptr<Effect<P>>>{},
                                              std::vector<std::unique_ptr<Probe>>{});
}

}  // namespace bsmpm::test

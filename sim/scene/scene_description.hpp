// A scene as plain, validated data: what the TOML file says, with defaults filled in and
// every value checked. Building the simulation from it (scene_builder) fails on input only
// where seeding decides: a shape too small to hold a particle at the grid's resolution.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/boundaries.hpp"
#include "core/error.hpp"
#include "core/types.hpp"
#include "materials/material.hpp"
#include "particles/shapes.hpp"
#include "probes/probe.hpp"
#include "scene/effect_registry.hpp"
#include "step/simulation.hpp"
#include "step/time_step.hpp"

namespace bsmpm {

enum class InitialStress { kNone, kHydrostatic };

struct BodyDescription {
  std::string name;
  std::string material_name;
  Material material;
  Shape shape;
  Vec2 velocity = Vec2::Zero();
  InitialStress initial_stress = InitialStress::kNone;
  SourceLocation where;
};

struct ProbeDescription {
  enum class Kind { kWallPressure, kWallReaction, kSurfacePressure, kMaterialPoint, kFront };
  std::string name;
  Kind kind = Kind::kWallPressure;
  int wall = 0;                    // WallSide, for kWallPressure and kWallReaction
  double position = 0.0;           // along the wall [m]
  std::optional<int> body;         // for kSurfacePressure, kMaterialPoint, kFront
  Vec2 point = Vec2::Zero();       // reference position on the body
  Vec2 normal = Vec2::Zero();      // into the fluid (kSurfacePressure); direction (kFront)
  double size = 0.008;             // sensor footprint [m]
  std::optional<double> depth;     // default: one cell
  double interval = 0.0;           // 0: every step
};

struct SceneDescription {
  std::string path;          // the scene file
  std::string source_text;   // its text as read
  std::string effective_text;  // the table after --set overrides, re-serialised
  std::string title;

  Vec2 domain_min = Vec2::Zero(), domain_max = Vec2::Ones();

  double cell_size = 0.01;
  int order = 2;
  int particles_per_cell = 2;  // per axis

  TimeStepSettings time;
  double frame_interval = 0.01;
  ReferenceScales reference;
  SolverSettings solver;

  std::vector<BodyDescription> bodies;
  std::vector<ProbeDescription> probes;
  // The parameters of each optional effect (gravity, walls, contacts, ...), as the effect
  // read them, each absent when the scene does not ask for it (scene/effect_registry.hpp).
  EffectParameters effects;

  // The parameters of the effect that reads a T, or nullptr when the scene does not ask for it.
  template <class T>
  const T* effect_parameters() const {
    return effects.get<T>();
  }

  // Cells per axis and the actual cell size (the domain is split into whole cells).
  int cells_x() const;
  int cells_y() const;
  Rectangle domain() const { return {domain_min, domain_max}; }
  Vec2 actual_cell_size() const { return {(domain_max - domain_min).x() / cells_x(), (domain_max - domain_min).y() / cells_y()}; }
};

}  // namespace bsmpm

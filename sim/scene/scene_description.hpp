// A scene as plain, validated data: what the TOML file says, with defaults filled in and
// every value checked. Building the simulation from it (scene_builder) fails on input only
// where seeding decides: a shape too small to hold a particle at the grid's resolution.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "materials/material.hpp"
#include "particles/shapes.hpp"
#include "probes/probe.hpp"
#include "step/effects/tank_walls.hpp"
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
  std::vector<Rectangle> clamps;  // regions whose control points hold this body still
  SourceLocation where;
};

struct ProbeDescription {
  enum class Kind { kWallPressure, kSurfacePressure, kMaterialPoint, kFront };
  std::string name;
  Kind kind = Kind::kWallPressure;
  int wall = 0;                    // WallSide, for kWallPressure
  double position = 0.0;           // along the wall [m]
  int body = -1;                   // for kSurfacePressure, kMaterialPoint, kFront
  Vec2 point = Vec2::Zero();       // reference position on the body
  Vec2 normal = Vec2::Zero();      // into the fluid (kSurfacePressure); direction (kFront)
  double size = 0.008;             // sensor footprint [m]
  std::optional<double> depth;     // default: one cell
  double interval = 0.0;           // 0: every step
};

enum class ContactKind { kFrictionless, kCoulomb, kStick };

struct ContactDescription {
  int body_a = 0, body_b = 0;
  ContactKind kind = ContactKind::kFrictionless;
  double friction = 0.0;            // Coulomb coefficient
  bool distance_check = true;       // the Greville-position gap criterion (docs/method.md §6)
  SourceLocation where;
};

struct SceneDescription {
  std::string path;          // the scene file
  std::string source_text;   // its text as read
  std::string effective_text;  // the table after --set overrides, re-serialised
  std::string title;

  Vec2 domain_min = Vec2::Zero(), domain_max = Vec2::Ones();
  std::array<WallKind, 4> walls{WallKind::kSlip, WallKind::kSlip, WallKind::kSlip, WallKind::kSlip};

  double cell_size = 0.01;
  int order = 2;
  int particles_per_cell = 2;  // per axis

  TimeStepSettings time;
  double gravity = 9.81;
  double slope_deg = 0.0;
  double frame_interval = 0.01;
  ReferenceScales reference;
  SolverSettings solver;

  std::vector<BodyDescription> bodies;
  std::vector<ProbeDescription> probes;
  std::vector<ContactDescription> contacts;

  // Cells per axis and the actual cell size (the domain is split into whole cells).
  int cells_x() const;
  int cells_y() const;
  Vec2 actual_cell_size() const { return {(domain_max - domain_min).x() / cells_x(), (domain_max - domain_min).y() / cells_y()}; }
};

}  // namespace bsmpm

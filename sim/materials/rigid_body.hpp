// Rigid obstacle of prescribed motion: its particles move with a given velocity and act
// on other bodies only through contact (the limit m -> infinity of docs/method.md §5-§6).
#pragma once

#include <string>

#include "core/types.hpp"
#include "materials/material_attribute.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

// [materials.NAME] type = "rigid", density = 1000, velocity = [0, 0] (m/s).
struct RigidBody {
  static constexpr const char* kType = "rigid";
  static constexpr MaterialKind kKind = MaterialKind::kRigid;

  double density = 1000.0;  // mass of its particles on its own grid layer; the contact treats it as infinite
  Vec2 velocity = Vec2::Zero();

  static RigidBody read(TableReader& t) {
    RigidBody r;
    r.density = t.number_or("density", 1000.0, Range::positive());
    r.velocity = t.vec2_or("velocity", Vec2::Zero());
    return r;
  }

  // No waves: its prescribed speed alone bounds the time step, whatever the particle's own.
  double wave_speed(double) const { return 0.0; }
  double signal_speed(double, double) const { return velocity.norm(); }
  double stored_energy(const Mat2&, double) const { return 0.0; }
  // It carries no stress; the rigid motion effect describes it.
  std::string describe(const std::string&) const { return ""; }
  MaterialAttributes attributes() const { return {}; }
};

}  // namespace bsmpm

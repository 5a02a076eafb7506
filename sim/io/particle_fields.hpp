// The particle fields of a run, in one table. The run writer (HDF5 datasets), the XDMF
// sidecar and the run reader follow it, a test checks that docs/output-format.md lists the
// same fields, and a checkpoint is every field marked as state. A new particle field is
// one entry here (and its array in Particles).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "particles/particles.hpp"

namespace bsmpm {

enum class FieldType { kFloat64, kUInt16, kUInt32 };

// Where a field goes; an entry may have several.
enum FieldUse : unsigned {
  kInFrames = 1u << 0,         // run.h5 /frames/NNNNNN/<name>, every frame
  kInRunHeader = 1u << 1,      // run.h5 /particles/<name>, once: constant through a run
  kXdmfGeometry = 1u << 2,     // the points of the XDMF sidecar
  kXdmfAttribute = 1u << 3,    // an attribute of the XDMF sidecar
  kCheckpointState = 1u << 4,  // state a checkpoint must hold to resume bit for bit
};

struct ParticleField {
  std::string_view name;
  FieldType type;
  int components;
  std::string_view unit;  // SI, per metre of depth in 2D; "1" when dimensionless
  std::string_view component_names;  // "x,y", "xx,yy,xy", ...; empty for one component
  unsigned use;           // FieldUse bits
  // The components of the particle in slot p, into out[0 .. components).
  void (*get)(const Particles& particles, std::size_t p, double* out);
  // Sets the particle in slot p from in[0 .. components); nullptr for a field derived from
  // others (displacement, volume, ...), which a checkpoint does not hold.
  void (*set)(Particles& particles, std::size_t p, const double* in);

  bool has(FieldUse u) const { return (use & u) != 0; }
};

std::span<const ParticleField> particle_fields();

// The field's component names, split: {"xx", "yy", "xy"}; empty for one component.
std::vector<std::string> component_names(const ParticleField& field);

// The entry called `name`; throws std::logic_error when there is none (a programming error).
const ParticleField& particle_field(std::string_view name);

}  // namespace bsmpm

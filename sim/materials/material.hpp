// The closed set of constitutive models. Code visits the variant once per body and then
// runs a loop typed on the concrete model; nothing is dispatched per particle.
#pragma once

#include <string>
#include <variant>

#include "materials/elastic_solid.hpp"
#include "materials/rigid_body.hpp"
#include "materials/weakly_compressible_fluid.hpp"

namespace bsmpm {

using Material = std::variant<WeaklyCompressibleFluid, ElasticSolid, RigidBody>;

inline double density_of(const Material& m) {
  return std::visit([](const auto& mat) { return mat.density; }, m);
}

inline const char* kind_of(const Material& m) {
  struct Name {
    const char* operator()(const WeaklyCompressibleFluid&) const { return "fluid"; }
    const char* operator()(const ElasticSolid&) const { return "elastic"; }
    const char* operator()(const RigidBody&) const { return "rigid"; }
  };
  return std::visit(Name{}, m);
}

inline bool is_rigid(const Material& m) { return std::holds_alternative<RigidBody>(m); }
inline bool is_fluid(const Material& m) {
  return std::holds_alternative<WeaklyCompressibleFluid>(m);
}

}  // namespace bsmpm

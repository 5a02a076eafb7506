// The constitutive models a scene can name, registered as the effects are
// (scene/effect_registry.hpp). Code visits the variant once per body and then runs a loop
// typed on the concrete model; nothing is dispatched per particle.
//
// A new material is one header with a value type that satisfies MaterialModel below, plus its
// line in RegisteredMaterials; the step then needs its deformation and stress update
// (StressUpdate::update_body, step/passes/stress_update.hpp), which the compiler asks for.
#pragma once

#include <concepts>
#include <string>
#include <variant>
#include <vector>

#include "materials/elastic_solid.hpp"
#include "materials/incompressible_fluid.hpp"
#include "materials/material_attribute.hpp"
#include "materials/rigid_body.hpp"
#include "materials/weakly_compressible_fluid.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

template <class M>
concept MaterialModel = requires(const M m, TableReader& t, const Mat2& F, double J, const std::string& body) {
  { M::kType } -> std::convertible_to<const char*>;          // its `type` in [materials.NAME]
  { M::kKind } -> std::convertible_to<MaterialKind>;          // its role: fluid, elastic or rigid
  { M::read(t) } -> std::same_as<M>;                          // reads its own keys (not `type`)
  { m.density } -> std::convertible_to<double>;               // rho0 [kg/m3]
  { m.wave_speed(J) } -> std::convertible_to<double>;         // at volume ratio J; 0 without waves
  { m.signal_speed(J, J) } -> std::convertible_to<double>;    // c + |v| (CFL), given J and |v|
  { m.stored_energy(F, J) } -> std::convertible_to<double>;   // per unit reference volume
  { m.describe(body) } -> std::convertible_to<std::string>;   // start-of-run line ("" for none)
  { m.attributes() } -> std::same_as<MaterialAttributes>;     // recorded in the run file
};

template <MaterialModel... Models>
struct MaterialList {
  using Variant = std::variant<Models...>;

  // The `type` values, in registration order.
  static std::vector<std::string> types() { return {Models::kType...}; }

  // [materials.NAME]: its `type` picks the model, which reads the rest; unknown keys fail.
  static Variant read(TableReader t) {
    const std::string type = t.choice("type", types());
    Variant m;
    ((type == Models::kType ? (m = Models::read(t), true) : false) || ...);
    t.finish();
    return m;
  }
};

// Every material a scene can name, one per line.
using RegisteredMaterials = MaterialList<
    WeaklyCompressibleFluid,
    IncompressibleFluid,
    ElasticSolid,
    RigidBody>;

using Material = RegisteredMaterials::Variant;

inline Material read_material(TableReader t) { return RegisteredMaterials::read(std::move(t)); }

inline MaterialKind kind_of(const Material& m) {
  return std::visit([](const auto& mat) { return std::decay_t<decltype(mat)>::kKind; }, m);
}
inline const char* kind_name(const Material& m) { return kind_name(kind_of(m)); }

inline double density_of(const Material& m) {
  return std::visit([](const auto& mat) { return mat.density; }, m);
}

// c + |v| for a particle of this material at volume ratio J moving at `speed`.
inline double signal_speed(const Material& m, double J, double speed) {
  return std::visit([&](const auto& mat) { return mat.signal_speed(J, speed); }, m);
}

inline double wave_speed(const Material& m, double J) {
  return std::visit([&](const auto& mat) { return mat.wave_speed(J); }, m);
}

inline bool is_rigid(const Material& m) { return kind_of(m) == MaterialKind::kRigid; }
inline bool is_fluid(const Material& m) { return kind_of(m) == MaterialKind::kFluid; }
inline bool is_elastic(const Material& m) { return kind_of(m) == MaterialKind::kElastic; }
inline bool is_incompressible(const Material& m) { return std::holds_alternative<IncompressibleFluid>(m); }

}  // namespace bsmpm

// The tables of a scene being loaded, as the parts of the program that own some of its keys
// see them (each effect reads its own parameters: see scene/effect_registry.cpp). A reader
// takes only the keys it owns; the loader finishes the shared tables ([domain], [solver],
// each [[bodies]] entry) once every reader has run, so a key nobody read is still an error.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "materials/material.hpp"
#include "parameters/table_reader.hpp"
#include "particles/shapes.hpp"

namespace bsmpm {

// One [[bodies]] entry, with what the loader has read from it already.
struct BodyTable {
  TableReader& table;
  const std::string& name;
  const Material& material;
  const Shape& shape;
};

struct SceneTables {
  TableReader& root;            // the top level: tables of their own, e.g. [gravity]
  TableReader& domain;          // [domain]
  TableReader* solver;          // [solver]; nullptr when the scene has none
  Rectangle domain_box;         // domain.min .. domain.max
  std::vector<BodyTable> bodies;

  // Index of the body called `name`; fails at `key` of `t` when there is none.
  int find_body(const TableReader& t, std::string_view key, const std::string& name) const {
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == name) return static_cast<int>(b);
    t.fail(key, "no body named \"" + name + "\"");
  }
};

}  // namespace bsmpm

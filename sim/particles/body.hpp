// A body: one material, one contiguous particle range, one grid velocity field (layer).
#pragma once

#include <cstddef>
#include <string>

#include "core/types.hpp"
#include "materials/material.hpp"

namespace bsmpm {

struct Body {
  std::string name;
  Material material;
  std::size_t begin = 0, end = 0;  // particle range [begin, end)
  int layer = 0;                   // grid velocity field this body maps to
  Vec2 spacing = Vec2::Zero();     // initial particle spacing (dx, dy)

  std::size_t size() const { return end - begin; }
};

}  // namespace bsmpm

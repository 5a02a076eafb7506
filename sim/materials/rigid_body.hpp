// Rigid obstacle of prescribed motion: its particles move with a given velocity and act
// on other bodies only through contact (the limit m -> infinity of docs/method.md §5-§6).
#pragma once

#include "core/types.hpp"

namespace bsmpm {

struct RigidBody {
  double density = 1000.0;  // mass of its particles on its own grid layer; the contact treats it as infinite
  Vec2 velocity = Vec2::Zero();
};

}  // namespace bsmpm

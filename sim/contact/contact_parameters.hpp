// The scene's [[contacts]]: which pairs of bodies interact through contact and how
// (docs/method.md §6; docs/scene-format.md). The scene builder gives every body in a contact
// its own grid field; LiLian2024Contact enforces the pairs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/boundaries.hpp"
#include "step/effects/scene_tables.hpp"

namespace bsmpm {

// [[contacts]] bodies = ["r", "s"], type = "frictionless" | "coulomb" | "stick",
// friction = mu (coulomb only), distance_check = true.
struct ContactParameters {
  std::vector<ContactPair> pairs;

  // Also checks that every rigid body is in a pair: it acts on nothing otherwise.
  static std::optional<ContactParameters> read(SceneTables& scene) {
    ContactParameters p;
    for (auto& t : scene.root.tables("contacts")) {
      ContactPair c;
      {
        const auto names = t.string_pair("bodies");
        c.body_r = scene.find_body(t, "bodies", names[0]);
        c.body_s = scene.find_body(t, "bodies", names[1]);
        if (c.body_r == c.body_s) t.fail("bodies", "a contact needs two different bodies");
      }
      const std::string kind = t.choice("type", {"frictionless", "coulomb", "stick"});
      c.kind = kind == "frictionless" ? ContactKind::kFrictionless
               : kind == "coulomb"    ? ContactKind::kCoulomb
                                      : ContactKind::kStick;
      if (c.kind == ContactKind::kCoulomb) c.friction = t.number("friction", Range::non_negative());
      else if (t.has("friction")) t.fail("friction", "only applies to type = \"coulomb\"");
      c.distance_check = t.boolean_or("distance_check", true);
      for (const ContactPair& other : p.pairs)
        if ((other.body_r == c.body_r && other.body_s == c.body_s) ||
            (other.body_r == c.body_s && other.body_s == c.body_r))
          t.fail("bodies", "this pair already has a contact");
      t.finish();
      p.pairs.push_back(c);
    }
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if (!is_rigid(scene.bodies[b].material) || p.involves(static_cast<int>(b))) continue;
      const TableReader& body = scene.bodies[b].table;
      throw SceneError(body.where(), body.dotted("material"),
                       "rigid body \"" + scene.bodies[b].name +
                           "\" acts only through contact: add a [[contacts]] entry for it");
    }
    if (p.pairs.empty()) return std::nullopt;
    return p;
  }

  bool involves(int body) const {
    for (const ContactPair& c : pairs)
      if (c.body_r == body || c.body_s == body) return true;
    return false;
  }
};

}  // namespace bsmpm

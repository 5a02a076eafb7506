// What a body meets at its boundary: the four walls of the tank (docs/method.md §3) and the
// declared contacts with other bodies (§6). Plain types shared by the scene description,
// the effects that enforce them and the probes; this header includes nothing of the solver.
#pragma once

#include <string>
#include <vector>

namespace bsmpm {

enum WallSide { kLeft = 0, kRight = 1, kBottom = 2, kTop = 3 };

// "left", "right", "bottom", "top", indexed by WallSide (the scene's names).
inline const std::vector<std::string>& wall_side_names() {
  static const std::vector<std::string> names = {"left", "right", "bottom", "top"};
  return names;
}
inline const char* wall_side_name(int side) { return wall_side_names()[side].c_str(); }

enum class WallKind { kSlip, kSymmetry, kNoSlip };

inline const char* wall_kind_name(WallKind k) {
  return k == WallKind::kSlip ? "slip" : k == WallKind::kSymmetry ? "symmetry" : "no_slip";
}

enum class ContactKind { kFrictionless, kCoulomb, kStick };

// One declared contact between bodies r and s (indices into the scene's bodies; r is the
// first body named in the scene).
struct ContactPair {
  int body_r = 0, body_s = 0;
  ContactKind kind = ContactKind::kFrictionless;
  double friction = 0.0;       // Coulomb coefficient mu (kind kCoulomb)
  bool distance_check = true;  // the Greville-position gap criterion (docs/method.md §6)
};

}  // namespace bsmpm

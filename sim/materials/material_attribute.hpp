// One named property of a material as the run file records it (docs/output-format.md): the
// writer stores whatever a material lists, so a new material needs no change there.
#pragma once

#include <string>
#include <variant>
#include <vector>

namespace bsmpm {

// The role of a material in the step and in the files: what the renderer draws as water
// ("fluid") or as a solid, which bodies the walls' pressure and particle shifting act on.
enum class MaterialKind { kFluid, kElastic, kRigid };

inline const char* kind_name(MaterialKind kind) {
  return kind == MaterialKind::kFluid ? "fluid" : kind == MaterialKind::kElastic ? "elastic" : "rigid";
}

struct MaterialAttribute {
  std::string name;
  std::variant<double, std::string> value;
};

using MaterialAttributes = std::vector<MaterialAttribute>;

}  // namespace bsmpm

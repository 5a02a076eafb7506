// Fuzzes the scene loader (load_scene_text): any text is a scene or a SceneError (or
// another bsmpm::Error); nothing else may escape, crash, hang or trip a sanitizer.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "scene/scene_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)bsmpm::load_scene_text(text, "fuzz.toml");
  } catch (const bsmpm::Error&) {
  }
  return 0;
}

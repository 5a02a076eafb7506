// Fuzzes the study loader (load_study_text): any text is a study or a bsmpm::Error. The
// study's path lies in the source tree's scenes/studies/ so that a relative base scene
// ("../scenes/...") can be found, as the committed corpus has it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "study/study_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)bsmpm::load_study_text(text, BSMPM_SOURCE_DIR "/scenes/studies/fuzz.toml");
  } catch (const bsmpm::Error&) {
  }
  return 0;
}

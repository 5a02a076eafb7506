// Replays a fuzzer's committed corpus (tests/fuzz/corpus/NAME) through its
// LLVMFuzzerTestOneInput without libFuzzer, so that the ordinary test suite runs every input
// the fuzzing found: an input that now escapes with anything but a bsmpm::Error aborts the
// program (the fuzzer lets it escape) and fails its test.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  long inputs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1])) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    ++inputs;
  }
  std::printf("%ld inputs replayed from %s\n", inputs, argv[1]);
  return inputs > 0 ? 0 : 1;  // an empty or missing corpus is no replay
}

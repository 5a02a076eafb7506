// The layering of docs/architecture.md, checked on the sources: every #include "X/..." in
// sim/ and render/ names a folder at the same level or below its own, so no dependency
// points up (render -> sim, never back; inside each library, the order below).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Each library's folders, lowest first; a folder may include its own files and those of
// the folders before it (and render all of sim). A subfolder (step/passes, step/effects)
// belongs to its folder.
const std::vector<std::string> kSimLayers = {"core",  "bspline", "parameters",  "materials", "grid",
                                             "particles", "probes", "step", "contact", "diagnostics",
                                             "io",    "scene",   "study"};
const std::vector<std::string> kRenderLayers = {"output", "image", "color",    "text",    "gl", "movie",
                                                "figure", "paint", "settings", "compose", "cli"};

struct Layer {
  int library = 0;  // 0: sim, 1: render
  int rank = 0;
};

std::map<std::string, Layer> layers() {
  std::map<std::string, Layer> out;
  for (std::size_t k = 0; k < kSimLayers.size(); ++k) out[kSimLayers[k]] = {0, static_cast<int>(k)};
  for (std::size_t k = 0; k < kRenderLayers.size(); ++k) out[kRenderLayers[k]] = {1, static_cast<int>(k)};
  return out;
}

// The includes in quotes of every source file of `library` (sim or render), as
// (file relative to the repository, line, included path).
struct Include {
  std::string file;
  int line;
  std::string path;
};

std::vector<Include> includes_of(const std::string& library) {
  static const std::regex include_line(R"(^\s*#\s*include\s+"([^"]+)\")");
  const fs::path root = fs::path(BSMPM_SOURCE_DIR) / library;
  std::vector<Include> out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".hpp" && ext != ".cpp" && ext != ".h" && ext != ".in") continue;
    std::ifstream in(entry.path());
    int n = 0;
    std::smatch m;
    for (std::string text; std::getline(in, text);)
      if (++n, std::regex_search(text, m, include_line))
        out.push_back({fs::relative(entry.path(), BSMPM_SOURCE_DIR).string(), n, m[1]});
  }
  return out;
}

// The folder a file or an included path belongs to: its first component below the library.
std::string folder_of(const std::string& path, bool source_file) {
  const fs::path p(path);
  auto it = p.begin();
  if (source_file) ++it;  // sim/ or render/
  return it == p.end() ? "" : it->string();
}

std::vector<std::string> upward_includes(const std::string& library) {
  const auto known = layers();
  std::vector<std::string> wrong;
  for (const Include& inc : includes_of(library)) {
    const std::string where = inc.file + ":" + std::to_string(inc.line) + " includes \"" + inc.path + "\"";
    const auto from = known.find(folder_of(inc.file, true));
    const auto to = known.find(folder_of(inc.path, false));
    if (from == known.end() || to == known.end()) {
      wrong.push_back(where + ": a folder the layering does not list (tests/unit/layering_test.cpp)");
      continue;
    }
    const Layer a = from->second, b = to->second;
    if (b.library > a.library || (b.library == a.library && b.rank > a.rank))
      wrong.push_back(where + ": up from " + from->first + " to " + to->first);
    // The step itself (sim/step/ and its passes) never includes an effect: effects plug into
    // it (step/effect.hpp).
    const std::string dir = fs::path(inc.file).parent_path().string();
    if ((dir == "sim/step" || dir == "sim/step/passes") && inc.path.rfind("step/effects/", 0) == 0)
      wrong.push_back(where + ": the step includes an effect");
  }
  return wrong;
}

}  // namespace

TEST_CASE("No include points up across folders: sim never includes render, each library in its order",
          "[layering]") {
  for (const std::string library : {"sim", "render"}) {
    INFO(library);
    const auto all = includes_of(library);
    REQUIRE(all.size() > 100);  // the files were found
    const auto wrong = upward_includes(library);
    std::string listing;
    for (const auto& w : wrong) listing += w + "\n";
    INFO(listing);
    CHECK(wrong.empty());
  }
}

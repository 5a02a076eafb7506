// The table of particle fields (sim/io/particle_fields.cpp): docs/output-format.md lists the
// same run-file fields, and the state fields hold every array of Particles, so that a
// checkpoint made of them restores the particles bit for bit.
#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "io/particle_fields.hpp"
#include "test_support.hpp"

using namespace bsmpm;

namespace {

struct DocumentedField {
  bool in_frames = false;
  std::string type;
  int components = 1;
  std::string unit;
};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* type_name(FieldType t) {
  switch (t) {
    case FieldType::kFloat64: return "float64";
    case FieldType::kUInt16: return "uint16";
    default: return "uint32";
  }
}

}  // namespace

TEST_CASE("docs/output-format.md lists the particle fields of the run file", "[output][docs]") {
  const std::string doc = read_text(test::source_path("docs/output-format.md"));
  REQUIRE(!doc.empty());

  // | `/frames/NNNNNN/velocity` | float64 [N, 2] | m/s | ... |
  const std::regex row(R"(\| `/(particles|frames/NNNNNN)/([a-z_]+)` \| (\w+) \[N(?:, (\d+))?\] \| ([^|]+?) \|)");
  std::map<std::string, DocumentedField> documented;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), row); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    DocumentedField f;
    f.in_frames = m[1] != "particles";
    f.type = m[3];
    f.components = m[4].matched ? std::stoi(m[4]) : 1;
    f.unit = m[5];
    CHECK(documented.emplace(m[2], f).second);
  }

  std::map<std::string, DocumentedField> table;
  std::vector<std::string> xdmf_attributes;
  for (const ParticleField& field : particle_fields()) {
    // A tensor (more than two components) goes to the sidecar as a scalar per component.
    if (field.has(kXdmfAttribute) && field.components <= 2) xdmf_attributes.emplace_back(field.name);
    if (field.has(kXdmfAttribute) && field.components > 2)
      for (const std::string& c : component_names(field)) xdmf_attributes.push_back(std::string(field.name) + "_" + c);
    if (!field.has(kInFrames) && !field.has(kInRunHeader)) continue;
    table[std::string(field.name)] = {field.has(kInFrames), type_name(field.type), field.components,
                                      std::string(field.unit)};
  }

  std::vector<std::string> documented_names, table_names;
  for (const auto& [name, f] : documented) documented_names.push_back(name);
  for (const auto& [name, f] : table) table_names.push_back(name);
  REQUIRE(documented_names == table_names);
  for (const auto& [name, f] : table) {
    INFO("field " << name);
    const DocumentedField& d = documented[name];
    CHECK(d.in_frames == f.in_frames);
    CHECK(d.type == f.type);
    CHECK(d.components == f.components);
    CHECK(d.unit == f.unit);
  }

  // "... with the attributes pressure, velocity, ..., volume and body, pointing into run.h5"
  std::smatch m;
  const std::string flat = std::regex_replace(doc, std::regex("\\s+"), " ");
  REQUIRE(std::regex_search(flat, m, std::regex("with the attributes ([a-z_, ]+) and ([a-z_]+), pointing")));
  std::vector<std::string> listed;
  const std::string first = m[1];
  const std::regex comma(", ");
  for (std::sregex_token_iterator it(first.begin(), first.end(), comma, -1), end; it != end; ++it)
    listed.push_back(*it);
  listed.push_back(m[2]);
  CHECK(listed == xdmf_attributes);
}

TEST_CASE("The state fields hold every array of Particles, bit for bit", "[output][checkpoint]") {
  std::size_t state_fields = 0;
  for (const ParticleField& field : particle_fields())
    if (field.has(kCheckpointState)) {
      ++state_fields;
      CHECK(field.set != nullptr);
    }
  // Every member of Particles is one std::vector: a new one needs its entry in the table.
  CHECK(state_fields == sizeof(Particles) / sizeof(std::vector<double>));

  Particles a, b;
  for (int p = 0; p < 5; ++p) {
    a.push_back(Vec2(p + 0.1, p + 0.2), 1.0 + p, 2.0 + p, static_cast<BodyId>(3 + p));
    b.push_back(Vec2::Zero(), 0.0, 0.0, 0);
    a.x0[p] = Vec2(p + 0.3, p + 0.4);
    a.v[p] = Vec2(-p - 0.5, p + 0.6);
    a.J[p] = 1.0 + 1e-3 * p;
    a.F[p] << 1.1 + p, 0.2, -0.3, 0.9;
    a.stress[p] << -1.0e3 * p, 1.0 / 3.0, 1.0 / 7.0, 2.5;  // not symmetric: all four entries count
    a.pressure[p] = 1.0e3 * p + 0.7;
    a.id[p] = 1000 + p;
  }
  std::vector<double> values;
  for (const ParticleField& field : particle_fields()) {
    if (!field.has(kCheckpointState)) continue;
    values.resize(field.components);
    for (std::size_t p = 0; p < a.size(); ++p) {
      field.get(a, p, values.data());
      field.set(b, p, values.data());
    }
  }
  CHECK(b.x == a.x);
  CHECK(b.x0 == a.x0);
  CHECK(b.v == a.v);
  CHECK(b.mass == a.mass);
  CHECK(b.volume0 == a.volume0);
  CHECK(b.J == a.J);
  CHECK(b.F == a.F);
  CHECK(b.stress == a.stress);
  CHECK(b.pressure == a.pressure);
  CHECK(b.id == a.id);
  CHECK(b.body == a.body);
}

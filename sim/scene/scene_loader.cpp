#include "scene/scene_loader.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "scene/overrides.hpp"
#include "scene/toml_reader.hpp"

namespace bsmpm {

namespace {

const std::vector<std::string> kWallNames = {"left", "right", "bottom", "top"};
const char* const kForeignTables[] = {"render"};

void read_domain(TableReader t, SceneDescription& s) {
  s.domain_min = t.vec2("min");
  s.domain_max = t.vec2("max");
  if (!(s.domain_max.x() > s.domain_min.x() && s.domain_max.y() > s.domain_min.y()))
    t.fail("max", "must exceed domain.min in both x and y");
  if (auto walls = t.optional_table("walls")) {
    for (int side = 0; side < 4; ++side) {
      const std::string kind = walls->choice_or(kWallNames[side], "slip", {"slip", "symmetry", "no_slip"});
      s.walls[side] = kind == "slip" ? WallKind::kSlip : kind == "symmetry" ? WallKind::kSymmetry : WallKind::kNoSlip;
    }
    walls->finish();
  }
  t.finish();
}

void read_grid(TableReader t, SceneDescription& s) {
  s.cell_size = t.number("cell_size", Range::positive());
  s.order = static_cast<int>(t.integer_or("order", 2, 1, 3));
  s.particles_per_cell = static_cast<int>(t.integer_or("particles_per_cell", 2, 1, 8));
  const Vec2 size = s.domain_max - s.domain_min;
  const double cells_min = std::min(size.x(), size.y()) / s.cell_size;
  if (cells_min < 2.0 * s.order)
    t.fail("cell_size", "leaves fewer than " + std::to_string(2 * s.order) + " cells across the domain");
  const double cells_total = (size.x() / s.cell_size) * (size.y() / s.cell_size);
  if (cells_total > 2.0e8) t.fail("cell_size", "gives more than 2e8 cells; the grid would not fit in memory");
  t.finish();
}

void read_time(TableReader t, SceneDescription& s) {
  s.time.end = t.number("end", Range::positive());
  if (t.has("dt") && t.has("cfl"))
    t.fail("cfl", "give either time.dt (fixed step) or time.cfl (adaptive step), not both");
  if (t.has("dt")) {
    s.time.mode = TimeStepSettings::Mode::kFixed;
    s.time.dt = t.number("dt", Range::positive());
    if (t.has("max_dt")) t.fail("max_dt", "only applies to the adaptive step (time.cfl)");
  } else {
    s.time.mode = TimeStepSettings::Mode::kCfl;
    s.time.cfl = t.number_or("cfl", 0.3, {0.0, 1.0, true, false});
    s.time.max_dt = t.number_or("max_dt", 1.0e-3, Range::positive());
  }
  t.finish();
}

Material read_material(TableReader t) {
  const std::string type = t.choice("type", {"fluid", "elastic", "rigid"});
  Material m;
  if (type == "fluid") {
    WeaklyCompressibleFluid f;
    f.density = t.number("density", Range::positive());
    if (t.has("bulk_modulus") == t.has("sound_speed"))
      t.fail(t.has("bulk_modulus") ? "sound_speed" : "bulk_modulus",
             "give exactly one of bulk_modulus [Pa] and sound_speed [m/s]");
    if (t.has("bulk_modulus")) f.bulk_modulus = t.number("bulk_modulus", Range::positive());
    else {
      const double c = t.number("sound_speed", Range::positive());
      f.bulk_modulus = f.density * c * c;
    }
    f.viscosity = t.number_or("viscosity", 0.0, Range::non_negative());
    f.eos = t.choice_or("equation_of_state", "tait", {"tait", "linear"}) == "tait" ? EquationOfState::kTait
                                                                                   : EquationOfState::kLinear;
    if (f.eos == EquationOfState::kTait) f.tait_gamma = t.number_or("tait_gamma", 7.0, {1.0, 20.0, true, false});
    if (t.has("min_pressure")) f.min_pressure = t.number("min_pressure", {-1e300, 0.0, false, false});
    m = f;
  } else if (type == "elastic") {
    ElasticSolid e;
    e.density = t.number("density", Range::positive());
    e.youngs_modulus = t.number("youngs_modulus", Range::positive());
    e.poisson_ratio = t.number_or("poisson_ratio", 0.0, {0.0, 0.5, false, true});
    e.model = t.choice_or("elastic_model", "neo_hookean", {"neo_hookean", "saint_venant_kirchhoff"}) == "neo_hookean"
                  ? ElasticModel::kNeoHookean
                  : ElasticModel::kSaintVenantKirchhoff;
    m = e;
  } else {
    RigidBody r;
    r.density = t.number_or("density", 1000.0, Range::positive());
    r.velocity = t.vec2_or("velocity", Vec2::Zero());
    m = r;
  }
  t.finish();
  return m;
}

Rectangle read_rectangle(TableReader& t) {
  Rectangle r{t.vec2("min"), t.vec2("max")};
  if (!(r.max.x() > r.min.x() && r.max.y() > r.min.y())) t.fail("max", "must exceed min in both x and y");
  return r;
}

// Round-off allowance for geometry compared with the domain's edges.
double domain_tolerance(const SceneDescription& s) { return 1e-9 * (s.domain_max - s.domain_min).norm(); }

bool outside_domain(const Rectangle& r, const SceneDescription& s) {
  const double tol = domain_tolerance(s);
  return (r.min.array() < s.domain_min.array() - tol).any() || (r.max.array() > s.domain_max.array() + tol).any();
}

// A clamp region may be a segment or a point (max == min along an axis); it must lie in the
// domain and touch its body (a region beside the body would clamp nothing, or another body).
Rectangle read_region(TableReader& t, const Shape& body, const SceneDescription& s) {
  Rectangle r{t.vec2("min"), t.vec2("max")};
  if (!(r.max.x() >= r.min.x() && r.max.y() >= r.min.y())) t.fail("max", "must not be below min in x or y");
  if (outside_domain(r, s)) t.fail("min", "the region extends outside the domain");
  const double tol = domain_tolerance(s);
  const Rectangle box = bounding_box(body);
  if ((r.max.array() < box.min.array() - tol).any() || (r.min.array() > box.max.array() + tol).any())
    t.fail("min", "the region does not touch its body's shape");
  return r;
}

// A point that names a place on body `b` (a tracked material point, a pressure sensor): it
// must lie within one grid cell of the body's bounding box.
Vec2 read_point_on_body(TableReader& t, int b, const SceneDescription& s) {
  const Vec2 x = t.vec2("point");
  const Rectangle box = bounding_box(s.bodies[b].shape);
  const Vec2 h = s.actual_cell_size();
  if ((x.array() < box.min.array() - h.array()).any() || (x.array() > box.max.array() + h.array()).any())
    t.fail("point", "lies more than a grid cell away from body \"" + s.bodies[b].name + "\"");
  return x;
}

Shape read_shape(TableReader t, const SceneDescription& s) {
  const std::string type = t.choice("type", {"rectangle", "disk", "polygon"});
  Shape shape;
  if (type == "rectangle") {
    shape = read_rectangle(t);
  } else if (type == "disk") {
    Disk d{t.vec2("center"), t.number("radius", Range::positive())};
    shape = d;
  } else {
    Polygon p{t.points("points", 3)};
    shape = p;
    if (area(shape) <= 0.0) t.fail("points", "polygon has zero area");
  }
  if (outside_domain(bounding_box(shape), s)) t.fail("type", "shape extends outside the domain");
  t.finish();
  return shape;
}

void read_bodies(TableReader& root, SceneDescription& s, const std::map<std::string, Material>& materials) {
  auto bodies = root.tables("bodies");
  if (bodies.empty()) root.fail("bodies", "the scene has no [[bodies]]");
  for (auto& t : bodies) {
    BodyDescription b;
    b.where = t.where();
    b.name = t.string("name");
    for (const auto& other : s.bodies)
      if (other.name == b.name) t.fail("name", "a body named \"" + b.name + "\" already exists");
    b.material_name = t.string("material");
    const auto it = materials.find(b.material_name);
    if (it == materials.end()) t.fail("material", "no material \"" + b.material_name + "\" in [materials]");
    b.material = it->second;
    b.shape = read_shape(t.table("shape"), s);
    if (is_rigid(b.material) && t.has("velocity"))
      t.fail("velocity", "a rigid body moves at its material's velocity: set [materials." + b.material_name +
                             "].velocity");
    b.velocity = t.vec2_or("velocity", Vec2::Zero());
    const std::string stress = t.choice_or("initial_stress", "none", {"none", "hydrostatic"});
    b.initial_stress = stress == "hydrostatic" ? InitialStress::kHydrostatic : InitialStress::kNone;
    if (b.initial_stress == InitialStress::kHydrostatic && !is_fluid(b.material))
      t.fail("initial_stress", "\"hydrostatic\" applies to fluid bodies only");
    if (b.initial_stress == InitialStress::kHydrostatic && !(s.gravity > 0.0))
      t.fail("initial_stress", "\"hydrostatic\" needs gravity (gravity.g > 0)");
    for (auto& c : t.tables("clamp")) {
      b.clamps.push_back(read_region(c, b.shape, s));
      c.finish();
    }
    if (!b.clamps.empty() && is_rigid(b.material)) t.fail("clamp", "a rigid body's motion is prescribed already");
    t.finish();
    s.bodies.push_back(std::move(b));
  }
}

int find_body(TableReader& t, std::string_view key, const std::string& name, const SceneDescription& s) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (s.bodies[i].name == name) return static_cast<int>(i);
  t.fail(key, "no body named \"" + name + "\"");
}

int body_index(TableReader& t, std::string_view key, const SceneDescription& s) {
  return find_body(t, key, t.string(key), s);
}

void read_probes(TableReader& root, SceneDescription& s) {
  static const std::regex valid_name("[A-Za-z0-9_.-]+");
  for (auto& t : root.tables("probes")) {
    ProbeDescription p;
    p.name = t.string("name");
    if (!std::regex_match(p.name, valid_name)) t.fail("name", "use letters, digits, '_', '-' and '.' only (it names a file)");
    for (const auto& other : s.probes)
      if (other.name == p.name) t.fail("name", "a probe named \"" + p.name + "\" already exists");
    const std::string type = t.choice("type", {"wall_pressure", "surface_pressure", "material_point", "front"});
    p.interval = t.number_or("interval", 0.0, Range::non_negative());
    if (type == "front") {
      p.kind = ProbeDescription::Kind::kFront;
      p.body = body_index(t, "body", s);
      p.normal = t.vec2_or("direction", Vec2(1.0, 0.0));
      if (p.normal.norm() < 1e-12) t.fail("direction", "must be a non-zero vector");
    } else if (type == "material_point") {
      p.kind = ProbeDescription::Kind::kMaterialPoint;
      p.body = body_index(t, "body", s);
      p.point = read_point_on_body(t, p.body, s);
    } else {
      p.size = t.number_or("size", 0.008, Range::positive());
      if (t.has("depth")) p.depth = t.number("depth", Range::positive());
      if (type == "wall_pressure") {
        p.kind = ProbeDescription::Kind::kWallPressure;
        const std::string wall = t.choice("wall", kWallNames);
        p.wall = static_cast<int>(std::find(kWallNames.begin(), kWallNames.end(), wall) - kWallNames.begin());
        const bool vertical = p.wall == kLeft || p.wall == kRight;
        const double lo = vertical ? s.domain_min.y() : s.domain_min.x();
        const double hi = vertical ? s.domain_max.y() : s.domain_max.x();
        p.position = t.number("position", Range::closed(lo, hi));
      } else {
        p.kind = ProbeDescription::Kind::kSurfacePressure;
        p.body = body_index(t, "body", s);
        p.point = read_point_on_body(t, p.body, s);
        p.normal = t.vec2("normal");
        if (p.normal.norm() < 1e-12) t.fail("normal", "must be a non-zero vector");
      }
    }
    t.finish();
    s.probes.push_back(p);
  }
}

void read_contacts(TableReader& root, SceneDescription& s) {
  for (auto& t : root.tables("contacts")) {
    ContactDescription c;
    c.where = t.where();
    {
      auto pair = t.string_pair("bodies");
      int ids[2];
      for (int k = 0; k < 2; ++k) ids[k] = find_body(t, "bodies", pair[k], s);
      if (ids[0] == ids[1]) t.fail("bodies", "a contact needs two different bodies");
      c.body_a = ids[0];
      c.body_b = ids[1];
    }
    const std::string kind = t.choice("type", {"frictionless", "coulomb", "stick"});
    c.kind = kind == "frictionless" ? ContactKind::kFrictionless
             : kind == "coulomb"    ? ContactKind::kCoulomb
                                    : ContactKind::kStick;
    if (c.kind == ContactKind::kCoulomb) c.friction = t.number("friction", Range::non_negative());
    else if (t.has("friction")) t.fail("friction", "only applies to type = \"coulomb\"");
    c.distance_check = t.boolean_or("distance_check", true);
    for (const auto& other : s.contacts)
      if ((other.body_a == c.body_a && other.body_b == c.body_b) || (other.body_a == c.body_b && other.body_b == c.body_a))
        t.fail("bodies", "this pair already has a contact");
    t.finish();
    s.contacts.push_back(c);
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    if (!is_rigid(s.bodies[b].material)) continue;
    bool paired = false;
    for (const auto& c : s.contacts) paired = paired || c.body_a == int(b) || c.body_b == int(b);
    if (!paired)
      throw SceneError(s.bodies[b].where, "bodies[" + std::to_string(b) + "].material",
                       "rigid body \"" + s.bodies[b].name + "\" acts only through contact: add a [[contacts]] entry for it");
  }
}

}  // namespace

int SceneDescription::cells_x() const {
  return std::max(1, static_cast<int>(std::lround((domain_max - domain_min).x() / cell_size)));
}
int SceneDescription::cells_y() const {
  return std::max(1, static_cast<int>(std::lround((domain_max - domain_min).y() / cell_size)));
}

SceneDescription load_scene_text(const std::string& text, const std::string& path,
                                 const std::vector<std::string>& overrides,
                                 const std::vector<SceneExtension>& extensions) {
  toml::table root = parse_toml(text, path);
  for (const auto& o : overrides) apply_override(root, o);

  SceneDescription s;
  s.path = path;
  s.source_text = text;
  {
    std::ostringstream os;
    os << root;
    s.effective_text = os.str();
  }
  TableReader t(root, "", SourceLocation{path, 1, 1});
  if (auto meta = t.optional_table("scene")) {
    s.title = meta->string_or("title", "");
    meta->string_or("description", "");
    meta->finish();
  }
  read_domain(t.table("domain"), s);
  read_grid(t.table("grid"), s);
  read_time(t.table("time"), s);
  if (auto g = t.optional_table("gravity")) {
    s.gravity = g->number_or("g", 9.81, Range::non_negative());
    s.slope_deg = g->number_or("slope_deg", 0.0, Range::closed(-60.0, 60.0));
    g->finish();
  }
  s.frame_interval = s.time.end / 100.0;
  if (auto out = t.optional_table("output")) {
    s.frame_interval = out->number_or("frame_interval", s.frame_interval, Range::positive());
    out->finish();
  }
  if (auto solver = t.optional_table("solver")) {
    s.solver.flip_fraction = solver->number_or("flip", 1.0, Range::closed(0.0, 1.0));
    s.solver.mass_cutoff_ratio = solver->number_or("mass_cutoff", s.solver.mass_cutoff_ratio, Range::closed(0.0, 1.0));
    s.solver.sort_interval = static_cast<int>(solver->integer_or("sort_interval", 50, 0, 1000000));
    s.solver.smooth_fluid_volume = solver->boolean_or("smooth_fluid_volume", false);
    s.solver.local_damping = solver->number_or("local_damping", 0.0, {0.0, 1.0, false, true});
    solver->finish();
  }
  std::map<std::string, Material> materials;
  {
    auto mats = t.table("materials");
    for (auto& [name, table] : mats.named_tables()) materials.emplace(name, read_material(table));
    mats.finish();
  }
  read_bodies(t, s, materials);
  // Reference scales for T* and P*: the first fluid body's height and density by default.
  s.reference.gravity = s.gravity > 0.0 ? s.gravity : 9.81;
  for (const auto& b : s.bodies)
    if (is_fluid(b.material)) {
      const Rectangle box = bounding_box(b.shape);
      s.reference.length = box.max.y() - box.min.y();
      s.reference.density = density_of(b.material);
      break;
    }
  if (auto ref = t.optional_table("reference")) {
    s.reference.length = ref->number_or("length", s.reference.length, Range::positive());
    s.reference.density = ref->number_or("density", s.reference.density, Range::positive());
    ref->finish();
  }
  read_probes(t, s);
  read_contacts(t, s);
  for (const auto& ext : extensions)
    if (auto table = t.optional_table(ext.table)) ext.validate(*table);
  // Tables owned by other parts of the program ([render]) are theirs to validate; a caller
  // that did not register them (the solver alone, the physics tests) passes them over.
  for (const char* owned : kForeignTables) {
    t.has(owned);  // known, for "did you mean" hints
    t.skip(owned);
  }
  t.finish();
  return s;
}

SceneDescription load_scene(const std::string& path, const std::vector<std::string>& overrides,
                            const std::vector<SceneExtension>& extensions) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return load_scene_text(text.str(), path, overrides, extensions);
}

}  // namespace bsmpm

#include "scene/scene_loader.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "core/input_file.hpp"
#include "step/effects/scene_tables.hpp"
#include "parameters/table_reader.hpp"
#include "scene/effect_registry.hpp"
#include "scene/overrides.hpp"
#include "step/effects/gravity.hpp"

namespace bsmpm {

namespace {

const char* const kForeignTables[] = {"render"};

// domain.min and domain.max; its walls are the tank walls effect's.
void read_domain(TableReader& t, SceneDescription& s) {
  s.domain_min = t.vec2("min");
  s.domain_max = t.vec2("max");
  if (!(s.domain_max.x() > s.domain_min.x() && s.domain_max.y() > s.domain_min.y()))
    t.fail("max", "must exceed domain.min in both x and y");
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
    s.time.cfl = t.number_or("cfl", 0.3, Range{Bound::exclusive(0.0), Bound::inclusive(1.0)});
    s.time.max_dt = t.number_or("max_dt", 1.0e-3, Range::positive());
  }
  t.finish();
}

Rectangle read_rectangle(TableReader& t) {
  Rectangle r{t.vec2("min"), t.vec2("max")};
  if (!(r.max.x() > r.min.x() && r.max.y() > r.min.y())) t.fail("max", "must exceed min in both x and y");
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
  if (extends_outside(bounding_box(shape), s.domain())) t.fail("type", "shape extends outside the domain");
  t.finish();
  return shape;
}

// The bodies' own keys; their tables stay open for the effects' keys (e.g. clamp) and are
// finished by the caller.
std::vector<TableReader> read_bodies(TableReader& root, SceneDescription& s,
                                     const std::map<std::string, Material>& materials) {
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
    s.bodies.push_back(std::move(b));
  }
  return bodies;
}

// A hydrostatic start needs the gravity effect (read after the bodies).
void check_hydrostatic_bodies(const std::vector<TableReader>& tables, const SceneDescription& s) {
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (s.bodies[b].initial_stress == InitialStress::kHydrostatic && !s.effect_parameters<GravityParameters>())
      tables[b].fail("initial_stress", "\"hydrostatic\" needs gravity (gravity.g > 0)");
}

int body_index(TableReader& t, std::string_view key, const SceneTables& scene) {
  return scene.find_body(t, key, t.string(key));
}

void read_probes(TableReader& root, SceneDescription& s, const SceneTables& scene) {
  static const std::regex valid_name("[A-Za-z0-9_.-]+");
  for (auto& t : root.tables("probes")) {
    ProbeDescription p;
    p.name = t.string("name");
    if (!std::regex_match(p.name, valid_name)) t.fail("name", "use letters, digits, '_', '-' and '.' only (it names a file)");
    if (p.name == "conservation") t.fail("name", "\"conservation\" is the run's own series (conservation.csv)");
    for (const auto& other : s.probes)
      if (other.name == p.name) t.fail("name", "a probe named \"" + p.name + "\" already exists");
    const std::string type =
        t.choice("type", {"wall_pressure", "wall_reaction", "surface_pressure", "material_point", "front"});
    p.interval = t.number_or("interval", 0.0, Range::non_negative());
    if (type == "front") {
      p.kind = ProbeDescription::Kind::kFront;
      p.body = body_index(t, "body", scene);
      p.normal = t.vec2_or("direction", Vec2(1.0, 0.0));
      if (p.normal.norm() < 1e-12) t.fail("direction", "must be a non-zero vector");
    } else if (type == "material_point") {
      p.kind = ProbeDescription::Kind::kMaterialPoint;
      p.body = body_index(t, "body", scene);
      p.point = read_point_on_body(t, *p.body, s);
    } else {
      p.size = t.number_or("size", 0.008, Range::positive());
      // A reaction sensor reads the wall itself: it has a face, no depth into the water.
      if (type != "wall_reaction" && t.has("depth")) p.depth = t.number("depth", Range::positive());
      if (type == "wall_pressure" || type == "wall_reaction") {
        p.kind = type == "wall_pressure" ? ProbeDescription::Kind::kWallPressure
                                         : ProbeDescription::Kind::kWallReaction;
        const std::vector<std::string>& walls = wall_side_names();
        const std::string wall = t.choice("wall", walls);
        p.wall = static_cast<int>(std::find(walls.begin(), walls.end(), wall) - walls.begin());
        const bool vertical = p.wall == kLeft || p.wall == kRight;
        const double lo = vertical ? s.domain_min.y() : s.domain_min.x();
        const double hi = vertical ? s.domain_max.y() : s.domain_max.x();
        p.position = t.number("position", Range::closed(lo, hi));
      } else {
        p.kind = ProbeDescription::Kind::kSurfacePressure;
        p.body = body_index(t, "body", scene);
        p.point = read_point_on_body(t, *p.body, s);
        p.normal = t.vec2("normal");
        if (p.normal.norm() < 1e-12) t.fail("normal", "must be a non-zero vector");
      }
    }
    t.finish();
    s.probes.push_back(p);
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
  TableReader domain = t.table("domain");
  read_domain(domain, s);
  read_grid(t.table("grid"), s);
  read_time(t.table("time"), s);
  s.frame_interval = s.time.end / 100.0;
  if (auto out = t.optional_table("output")) {
    s.frame_interval = out->number_or("frame_interval", s.frame_interval, Range::positive());
    out->finish();
  }
  std::optional<TableReader> solver = t.optional_table("solver");
  if (solver) {
    const bool apic = solver->choice_or("velocity_update", "flip", {"flip", "apic"}) == "apic";
    if (apic) s.solver.velocity_update = SolverSettings::VelocityUpdate::kApic;
    s.solver.flip_fraction = solver->number_or("flip", apic ? 0.0 : 1.0, Range::closed(0.0, 1.0));
    s.solver.mass_cutoff_ratio = solver->number_or("mass_cutoff", s.solver.mass_cutoff_ratio, Range::closed(0.0, 1.0));
    s.solver.sort_interval = static_cast<int>(solver->integer_or("sort_interval", 50, 0, 1000000));
    if (solver->boolean_or("smooth_fluid_volume", false)) s.solver.fluid_volume = SolverSettings::FluidVolume::kSmoothed;
    if (solver->has("fluid_volume")) {  // wins over smooth_fluid_volume
      const std::string volume = solver->choice("fluid_volume", {"particle", "smoothed", "projected"});
      s.solver.fluid_volume = volume == "particle"   ? SolverSettings::FluidVolume::kParticle
                              : volume == "smoothed" ? SolverSettings::FluidVolume::kSmoothed
                                                     : SolverSettings::FluidVolume::kProjected;
    }
    if (solver->has("smoothed_volume_readback")) {
      if (s.solver.fluid_volume != SolverSettings::FluidVolume::kSmoothed)
        solver->fail("smoothed_volume_readback", "applies only with fluid_volume = \"smoothed\"");
      s.solver.smoothed_values_only = solver->choice("smoothed_volume_readback", {"linear", "values"}) == "values";
    }
    if (solver->has("smoothed_volume_basis")) {
      if (s.solver.fluid_volume != SolverSettings::FluidVolume::kSmoothed)
        solver->fail("smoothed_volume_basis", "applies only with fluid_volume = \"smoothed\"");
      const std::string basis = solver->choice("smoothed_volume_basis", {"velocity", "linear", "linear_patches"});
      s.solver.smoothed_volume_basis = basis == "velocity" ? SolverSettings::SmoothedVolumeBasis::kVelocity
                                       : basis == "linear" ? SolverSettings::SmoothedVolumeBasis::kLinear
                                                           : SolverSettings::SmoothedVolumeBasis::kLinearPatches;
    }
    s.solver.shifting = solver->number_or("particle_shifting", 0.0, Range::closed(0.0, 0.5));
    s.solver.subcell_shifting = solver->number_or("subcell_shifting", 0.0, Range::closed(0.0, 0.25));
    if (solver->has("shifting_velocity")) {
      if (s.solver.shifting <= 0.0 && s.solver.subcell_shifting <= 0.0)
        solver->fail("shifting_velocity", "applies only with particle_shifting or subcell_shifting > 0");
      if (!apic)  // a FLIP particle has no affine field: its shift always keeps its velocity
        solver->fail("shifting_velocity", "applies only with velocity_update = \"apic\"");
      s.solver.shift_follows_affine = solver->choice("shifting_velocity", {"kept", "affine"}) == "affine";
    }
    const Vec2 range = solver->vec2_or("density_range", Vec2(s.solver.min_density_ratio, s.solver.max_density_ratio),
                                       Range::positive());
    if (!(range.x() < 1.0 && range.y() > 1.0)) solver->fail("density_range", "must be [low, high] with low < 1 < high");
    s.solver.min_density_ratio = range.x();
    s.solver.max_density_ratio = range.y();
  }
  std::map<std::string, Material> materials;
  {
    auto mats = t.table("materials");
    for (auto& [name, table] : mats.named_tables()) materials.emplace(name, read_material(table));
    mats.finish();
  }
  std::vector<TableReader> bodies = read_bodies(t, s, materials);
  for (const auto& b : s.bodies)  // an incompressible fluid's pressure is an impulse per step (method.md §12)
    if (is_incompressible(b.material)) s.time.even_steps_to_frames = true;

  // The effects read their own keys, some of them from tables shared with the loader.
  SceneTables scene{t, domain, solver ? &*solver : nullptr, s.domain(), {}};
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    scene.bodies.push_back({bodies[b], s.bodies[b].name, s.bodies[b].material, s.bodies[b].shape});
  s.effects = read_effects(scene);
  check_hydrostatic_bodies(bodies, s);
  for (const TableReader& body : bodies) body.finish();
  if (solver) solver->finish();
  domain.finish();

  // Reference scales for T* and P*: the first fluid body's height and density by default.
  const GravityParameters* gravity = s.effect_parameters<GravityParameters>();
  s.reference.gravity = gravity ? gravity->g : 9.81;
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
  read_probes(t, s, scene);
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
  return load_scene_text(read_input_file(path, "the scene file"), path, overrides, extensions);
}

}  // namespace bsmpm

#include "io/particle_fields.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace bsmpm {

namespace {

void put(double x, double* out) { out[0] = x; }
void put(std::uint16_t x, double* out) { out[0] = x; }
void put(std::uint32_t x, double* out) { out[0] = x; }
void put(const Vec2& v, double* out) {
  out[0] = v.x();
  out[1] = v.y();
}
void put(const Mat2& m, double* out) {  // row by row: xx, xy, yx, yy
  out[0] = m(0, 0);
  out[1] = m(0, 1);
  out[2] = m(1, 0);
  out[3] = m(1, 1);
}

void take(double& x, const double* in) { x = in[0]; }
void take(std::uint16_t& x, const double* in) { x = static_cast<std::uint16_t>(in[0]); }
void take(std::uint32_t& x, const double* in) { x = static_cast<std::uint32_t>(in[0]); }
void take(Vec2& v, const double* in) { v = Vec2(in[0], in[1]); }
void take(Mat2& m, const double* in) { m << in[0], in[1], in[2], in[3]; }

template <auto Array>
using Element = std::remove_cvref_t<decltype((std::declval<Particles&>().*Array)[0])>;

template <auto Array>
void get_state(const Particles& ps, std::size_t p, double* out) {
  put((ps.*Array)[p], out);
}
template <auto Array>
void set_state(Particles& ps, std::size_t p, const double* in) {
  take((ps.*Array)[p], in);
}

// A field that is one array of Particles: state a checkpoint holds.
template <auto Array>
constexpr ParticleField state(std::string_view name, std::string_view unit, unsigned use) {
  using T = Element<Array>;
  const FieldType type = std::is_same_v<T, std::uint16_t>   ? FieldType::kUInt16
                         : std::is_same_v<T, std::uint32_t> ? FieldType::kUInt32
                                                            : FieldType::kFloat64;
  const int components = std::is_same_v<T, Vec2> ? 2 : std::is_same_v<T, Mat2> ? 4 : 1;
  const std::string_view names = components == 2 ? "x,y" : components == 4 ? "xx,xy,yx,yy" : "";
  return {name, type, components, unit, names, use | kCheckpointState, &get_state<Array>, &set_state<Array>};
}

// A field computed from the state, for output only.
constexpr ParticleField derived(std::string_view name, int components, std::string_view unit, unsigned use,
                                void (*get)(const Particles&, std::size_t, double*),
                                std::string_view names = "") {
  return {name, FieldType::kFloat64, components, unit, names.empty() && components == 2 ? "x,y" : names, use, get,
          nullptr};
}

// The XDMF attributes follow this order (pressure first: what ParaView shows first).
constexpr ParticleField kFields[] = {
    state<&Particles::x>("position", "m", kInFrames | kXdmfGeometry),
    state<&Particles::pressure>("pressure", "Pa", kInFrames | kXdmfAttribute),
    state<&Particles::v>("velocity", "m/s", kInFrames | kXdmfAttribute),
    derived("displacement", 2, "m", kInFrames | kXdmfAttribute,
            [](const Particles& ps, std::size_t p, double* out) { put(Vec2(ps.x[p] - ps.x0[p]), out); }),
    // The in-plane Cauchy stress xx, yy, xy (plane strain); stress_tensor holds all of it.
    derived("stress", 3, "Pa", kInFrames | kXdmfAttribute,
            [](const Particles& ps, std::size_t p, double* out) {
              const Mat2& s = ps.stress[p];
              out[0] = s(0, 0);
              out[1] = s(1, 1);
              out[2] = s(0, 1);
            },
            "xx,yy,xy"),
    derived("volume", 1, "m2", kInFrames | kXdmfAttribute,
            [](const Particles& ps, std::size_t p, double* out) { out[0] = ps.volume(p); }),
    state<&Particles::body>("body", "1", kInRunHeader | kXdmfAttribute),
    state<&Particles::mass>("mass", "kg/m", kInRunHeader),
    state<&Particles::x0>("reference_position", "m", kInRunHeader),
    state<&Particles::volume0>("reference_volume", "m2", 0),
    state<&Particles::J>("volume_ratio", "1", 0),
    state<&Particles::F>("deformation_gradient", "1", 0),
    state<&Particles::stress>("stress_tensor", "Pa", 0),
    state<&Particles::C>("affine_velocity", "1/s", 0),
    state<&Particles::id>("id", "1", 0),
};

}  // namespace

std::span<const ParticleField> particle_fields() { return kFields; }

std::vector<std::string> component_names(const ParticleField& field) {
  std::vector<std::string> names;
  std::string_view rest = field.component_names;
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    names.emplace_back(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
  }
  return names;
}

const ParticleField& particle_field(std::string_view name) {
  for (const ParticleField& f : kFields)
    if (f.name == name) return f;
  throw std::logic_error("no particle field '" + std::string(name) + "' in io/particle_fields.cpp");
}

}  // namespace bsmpm

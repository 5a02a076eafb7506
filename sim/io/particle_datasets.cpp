#include "io/particle_datasets.hpp"

#include <string>

#include "core/error.hpp"
#include "io/hdf5.hpp"

namespace bsmpm {

namespace {

template <class T>
void write_integers(hid_t group, const std::string& name, const std::vector<double>& values) {
  const std::vector<T> v(values.begin(), values.end());
  h5::write_dataset(group, name, v.data(), v.size());
}

}  // namespace

void write_particle_dataset(hid_t group, const ParticleField& field, const Particles& particles,
                            const std::vector<std::uint32_t>* slot_of_row, std::vector<double>& buffer) {
  const std::size_t n = particles.size(), c = static_cast<std::size_t>(field.components);
  buffer.resize(n * c);
  for (std::size_t k = 0; k < n; ++k) field.get(particles, slot_of_row ? (*slot_of_row)[k] : k, &buffer[c * k]);
  const std::string name(field.name);
  if (field.type != FieldType::kFloat64 && c != 1)
    throw std::logic_error("io/particle_fields.cpp: the integer field '" + name + "' has " + std::to_string(c) +
                           " components; integer datasets hold one");
  switch (field.type) {
    case FieldType::kFloat64: h5::write_dataset(group, name, buffer.data(), n, c); break;
    case FieldType::kUInt16: write_integers<std::uint16_t>(group, name, buffer); break;
    case FieldType::kUInt32: write_integers<std::uint32_t>(group, name, buffer); break;
  }
  h5::Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "opening dataset " + name);
  h5::set_attribute(set, "units", std::string(field.unit));
  if (!field.component_names.empty()) h5::set_attribute(set, "components", std::string(field.component_names));
}

std::size_t field_value_bytes(const ParticleField& field) {
  const std::size_t bytes = field.type == FieldType::kUInt16 ? 2 : field.type == FieldType::kUInt32 ? 4 : 8;
  return bytes * static_cast<std::size_t>(field.components);
}

std::string xdmf_number_type(const ParticleField& field) {
  switch (field.type) {
    case FieldType::kFloat64: return "NumberType=\"Float\" Precision=\"8\"";
    case FieldType::kUInt16: return "NumberType=\"UInt\" Precision=\"2\"";
    case FieldType::kUInt32: return "NumberType=\"UInt\" Precision=\"4\"";
  }
  throw std::logic_error("io/particle_datasets.cpp: unknown field type of '" + std::string(field.name) + "'");
}

std::vector<double> read_particle_dataset(hid_t group, const ParticleField& field) {
  const std::string name(field.name);
  switch (field.type) {
    case FieldType::kFloat64: return h5::read_doubles(group, name);
    case FieldType::kUInt16: {
      const auto v = h5::read_uint16(group, name);
      return {v.begin(), v.end()};
    }
    case FieldType::kUInt32: {
      const auto v = h5::read_uint32(group, name);
      return {v.begin(), v.end()};
    }
  }
  throw std::logic_error("io/particle_datasets.cpp: unknown field type of '" + name + "'");
}

}  // namespace bsmpm

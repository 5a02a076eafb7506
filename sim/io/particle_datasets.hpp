// The HDF5 datasets of the particle fields (io/particle_fields.hpp): the one place that maps a
// field's type to its dataset type, for the run file and the checkpoint alike.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/particle_fields.hpp"

namespace bsmpm {

// Writes `field` as the dataset `field.name` under `group`, in the field's own type (float64
// [N, components], uint16 [N] or uint32 [N]) with the attributes `units` (its unit) and, with
// several components, `components` ("x,y", "xx,yy,xy"): row
// k holds the particle in slot (*slot_of_row)[k], or in slot k when slot_of_row is null.
// `buffer` is scratch space, kept between calls so that frames allocate nothing new.
void write_particle_dataset(hid_t group, const ParticleField& field, const Particles& particles,
                            const std::vector<std::uint32_t>* slot_of_row, std::vector<double>& buffer);

// Bytes of one particle's values of `field` as stored.
std::size_t field_value_bytes(const ParticleField& field);

// The XDMF description of that dataset's numbers: NumberType="..." Precision="...".
std::string xdmf_number_type(const ParticleField& field);

// The dataset `field.name` under `group` as doubles (exact for the integer types), row-major.
std::vector<double> read_particle_dataset(hid_t group, const ParticleField& field);

}  // namespace bsmpm

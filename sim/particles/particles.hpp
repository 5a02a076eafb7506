// Material points as structure-of-arrays. Each body owns one contiguous index range;
// within a range particles are kept sorted by cell (BsmpmSimulation::sort_particles_by_cell).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace bsmpm {

struct Particles {
  std::vector<Vec2> x;        // current position
  std::vector<Vec2> x0;       // reference (initial) position
  std::vector<Vec2> v;        // velocity
  std::vector<double> mass;
  std::vector<double> volume0;  // reference volume
  std::vector<double> J;        // volume ratio V / V0 (det F for solids)
  std::vector<Mat2> F;          // deformation gradient (solids; identity for fluids)
  std::vector<Mat2> stress;     // Cauchy stress, in-plane part (plane strain)
  std::vector<double> pressure; // fluids: equation of state; solids: -tr(sigma)/2
  std::vector<Mat2> C;          // affine velocity (APIC): v(x) = v_p + C (x - x_p); zero otherwise
  std::vector<std::uint32_t> id;  // index at creation; frames are written in id order
  std::vector<BodyId> body;

  std::size_t size() const { return x.size(); }

  void push_back(const Vec2& position, double m, double volume, BodyId b) {
    x.push_back(position);
    x0.push_back(position);
    v.push_back(Vec2::Zero());
    mass.push_back(m);
    volume0.push_back(volume);
    J.push_back(1.0);
    F.push_back(Mat2::Identity());
    stress.push_back(Mat2::Zero());
    pressure.push_back(0.0);
    C.push_back(Mat2::Zero());
    id.push_back(static_cast<std::uint32_t>(id.size()));
    body.push_back(b);
  }

  double volume(std::size_t p) const { return volume0[p] * J[p]; }
  std::size_t bytes() const {
    return heap_bytes(x) + heap_bytes(x0) + heap_bytes(v) + heap_bytes(mass) + heap_bytes(volume0) + heap_bytes(J) +
           heap_bytes(F) + heap_bytes(stress) + heap_bytes(pressure) + heap_bytes(C) + heap_bytes(id) +
           heap_bytes(body);
  }

  // Buffers for permute(), kept by the caller so that re-sorting allocates nothing.
  struct PermuteScratch {
    std::vector<Vec2> vec2;
    std::vector<double> real;
    std::vector<Mat2> mat2;
    std::vector<std::uint32_t> index;
    std::vector<BodyId> body;
    std::size_t bytes() const {
      return heap_bytes(vec2) + heap_bytes(real) + heap_bytes(mat2) + heap_bytes(index) + heap_bytes(body);
    }
  };
  // Reorders the range [begin, begin + order.size()) so that new slot k holds old
  // particle begin + order[k].
  void permute(std::size_t begin, const std::vector<std::uint32_t>& order, PermuteScratch& scratch);
};

}  // namespace bsmpm

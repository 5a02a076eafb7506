// Material points as structure-of-arrays. Each body owns one contiguous index range;
// within a range particles are kept sorted by cell (BsmpmSimulation::sort_particles_by_cell).
#pragma once

#include <cstddef>
#include <cstdint>
#include <tuple>
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

  // Calls visit(array) for every per-particle array above: the one list that bytes() and
  // permute() walk, so that a new array cannot be left out of either.
  template <class Visit>
  void for_each_array(Visit&& visit) {
    visit_arrays(*this, visit);
  }
  template <class Visit>
  void for_each_array(Visit&& visit) const {
    visit_arrays(*this, visit);
  }

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
    std::size_t sum = 0;
    for_each_array([&](const auto& a) { sum += heap_bytes(a); });
    return sum;
  }

  // Buffers for permute(), one per element type, kept by the caller so that re-sorting
  // allocates nothing.
  struct PermuteScratch {
    std::tuple<std::vector<Vec2>, std::vector<double>, std::vector<Mat2>, std::vector<std::uint32_t>,
               std::vector<BodyId>>
        buffers;
    template <class T>
    std::vector<T>& of() { return std::get<std::vector<T>>(buffers); }
    std::size_t bytes() const {
      return std::apply([](const auto&... b) { return (heap_bytes(b) + ...); }, buffers);
    }
  };
  // Reorders the range [begin, begin + order.size()) so that new slot k holds old
  // particle begin + order[k].
  void permute(std::size_t begin, const std::vector<std::uint32_t>& order, PermuteScratch& scratch);

 private:
  // The list behind both for_each_array(): `self` is a Particles or a const Particles.
  template <class Self, class Visit>
  static void visit_arrays(Self& self, Visit& visit) {
    visit(self.x), visit(self.x0), visit(self.v), visit(self.mass), visit(self.volume0), visit(self.J),
        visit(self.F), visit(self.stress), visit(self.pressure), visit(self.C), visit(self.id), visit(self.body);
  }
};

}  // namespace bsmpm

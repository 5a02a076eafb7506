// Small fixed-size tensors used throughout the solver (Eigen, no dynamic allocation).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>  // determinant() and inverse() of 2x2 matrices
#include <cstdint>
#include <vector>

namespace bsmpm {

using Real = double;
using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Mat2 = Eigen::Matrix<Real, 2, 2>;

// Body index of a particle; scenes hold at most a few dozen bodies.
using BodyId = std::uint16_t;

// Heap bytes a vector holds (its capacity, not its size).
template <class T>
std::size_t heap_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

inline constexpr Real kPi = 3.14159265358979323846;

}  // namespace bsmpm

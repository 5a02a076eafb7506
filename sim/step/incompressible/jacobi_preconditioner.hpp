// The diagonal of the pressure operator as a preconditioner of Eigen's conjugate gradients
// (the interface of Eigen's own DiagonalPreconditioner, which needs a stored matrix).
#pragma once

#include <Eigen/Core>

#include "step/incompressible/pressure_system.hpp"

namespace bsmpm {

template <int P>
class JacobiPreconditioner {
 public:
  JacobiPreconditioner() = default;
  template <class M>
  explicit JacobiPreconditioner(const M& m) { compute(m); }
  template <class M>
  JacobiPreconditioner& analyzePattern(const M&) { return *this; }
  template <class M>
  JacobiPreconditioner& factorize(const M& m) { return compute(m); }
  JacobiPreconditioner& compute(const PressureMatrix<P>& m) {
    const auto& d = m.system().diagonal();
    inverse_.resize(static_cast<Eigen::Index>(d.size()));
    for (std::size_t k = 0; k < d.size(); ++k) inverse_[k] = d[k] > 0.0 ? 1.0 / d[k] : 1.0;
    return *this;
  }
  template <class Rhs>
  Eigen::VectorXd solve(const Eigen::MatrixBase<Rhs>& b) const { return inverse_.cwiseProduct(b); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  Eigen::VectorXd inverse_;
};

}  // namespace bsmpm

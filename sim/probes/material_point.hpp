// A material point of a body followed through the run: the particle nearest to the
// requested reference position X, extrapolated with its deformation gradient,
// x(X) = x_p + F_p (X - X_p), so the point need not coincide with a particle centre.
#pragma once

#include <cstdint>
#include <vector>

#include "particles/body.hpp"
#include "particles/particles.hpp"
#include "probes/probe.hpp"

namespace bsmpm {

class MaterialPoint {
 public:
  MaterialPoint() = default;
  // Picks the particle of `body` nearest to X in the reference configuration.
  MaterialPoint(const Particles& particles, const Body& body, const Vec2& X);

  const Vec2& reference() const { return X_; }
  Vec2 position(const ProbeContext& ctx) const;
  // Current direction of a material normal N: F^{-T} N, normalised (Nanson's formula).
  Vec2 normal(const ProbeContext& ctx, const Vec2& N) const;

 private:
  std::uint32_t id_ = 0;
  Vec2 X_ = Vec2::Zero();
  Vec2 Xp_ = Vec2::Zero();
};

// Columns t, dx, dy, x, y.
class MaterialPointProbe final : public Probe {
 public:
  MaterialPointProbe(std::string name, double interval, MaterialPoint point, std::string body_name)
      : Probe(std::move(name), interval), point_(point), body_name_(std::move(body_name)) {}
  static std::vector<std::string> column_names() { return {"t", "dx", "dy", "x", "y"}; }
  std::vector<std::string> columns() const override { return column_names(); }
  std::vector<std::string> units() const override { return {"s", "m", "m", "m", "m"}; }
  std::string describe() const override;

 protected:
  void sample(const ProbeContext& ctx, double* row) override;

 private:
  MaterialPoint point_;
  std::string body_name_;
};

}  // namespace bsmpm

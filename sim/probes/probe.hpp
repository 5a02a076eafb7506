// Probes sample the state after a step and keep a time series (one row per sample).
// A scene without probes has none: sampling costs nothing then.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "particles/body.hpp"
#include "particles/particles.hpp"

namespace bsmpm {

struct ProbeContext {
  const Particles& particles;
  const std::vector<Body>& bodies;
  const std::vector<std::uint32_t>& index_of_id;
  double time;
  // The last step's wall impulses per control point (left, right, bottom, top; empty
  // before the first step) and its length, for sensors of the walls' reaction.
  const std::array<std::vector<Vec2>, 4>* wall_impulse = nullptr;
  double dt = 0.0;
};

// Scales for the non-dimensional columns: T* = t sqrt(g/H), P* = P / (rho g H).
struct ReferenceScales {
  double length = 1.0;    // H [m]
  double density = 1000.0;
  double gravity = 9.81;
  double time_factor() const;      // sqrt(g / H)
  double pressure_scale() const;   // rho g H
};

// What a probe carries from step to step: its next sample time and its rows (a checkpoint
// holds them, so a resumed run samples at the same times).
struct ProbeState {
  double next_time = -1.0e300;
  std::vector<double> data;  // row-major, row_count() x columns().size()
};

class Probe {
 public:
  Probe(std::string name, double interval) : name_(std::move(name)), interval_(interval) {}
  virtual ~Probe() = default;

  const std::string& name() const { return name_; }
  virtual std::vector<std::string> columns() const = 0;
  // The unit of each column ("s", "Pa", "m"; "1" for a number without unit).
  virtual std::vector<std::string> units() const = 0;
  virtual std::string describe() const = 0;

  // Samples when the interval since the last sample has elapsed (every call if 0).
  void maybe_sample(const ProbeContext& ctx);

  std::size_t row_count() const { return columns_count() ? data_.size() / columns_count() : 0; }
  const double* row(std::size_t r) const { return data_.data() + r * columns_count(); }
  const std::vector<double>& data() const { return data_; }
  ProbeState state() const { return {next_time_, data_}; }
  void restore(ProbeState state) {
    next_time_ = state.next_time;
    data_ = std::move(state.data);
  }

 protected:
  virtual void sample(const ProbeContext& ctx, double* row) = 0;

 private:
  // columns() builds its strings: counted once, so that sampling allocates nothing but the
  // series' own (amortised) growth.
  std::size_t columns_count() const {
    if (columns_count_ == 0) columns_count_ = columns().size();
    return columns_count_;
  }
  mutable std::size_t columns_count_ = 0;
  std::string name_;
  double interval_;
  double next_time_ = -1.0e300;
  std::vector<double> data_;
};

}  // namespace bsmpm

// A pressure sensor on a wall or on a body's face: the fluid pressure averaged over the
// sensor's footprint (docs/method.md §8: 8 mm by default), taken as the volume-weighted
// mean pressure of the fluid particles within `size` along the face and `depth` from it. A dry sensor reads 0.
// Columns t, T*, P, P* with T* = t sqrt(g/H) and P* = P / (rho g H).
#pragma once

#include <string>
#include <vector>

#include "probes/material_point.hpp"
#include "probes/probe.hpp"

namespace bsmpm {

struct PressureSensor {
  double size = 0.008;   // footprint along the face [m]
  double depth = 0.002;  // extent into the fluid [m]
};

class PressureProbe final : public Probe {
 public:
  // Fixed sensor (tank wall): centre, unit normal pointing into the fluid.
  PressureProbe(std::string name, double interval, Vec2 centre, Vec2 normal, PressureSensor sensor,
                std::vector<int> fluid_bodies, ReferenceScales scales, std::string where);
  // Sensor on a deforming body: centred on a material point of its face, normal N (into the
  // fluid) carried by the body's deformation.
  PressureProbe(std::string name, double interval, MaterialPoint anchor, Vec2 normal,
                PressureSensor sensor, std::vector<int> fluid_bodies, ReferenceScales scales,
                std::string where);

  static std::vector<std::string> column_names() { return {"t", "T*", "P", "P*"}; }
  std::vector<std::string> columns() const override { return column_names(); }
  static std::vector<std::string> column_units() { return {"s", "1", "Pa", "1"}; }
  std::vector<std::string> units() const override { return column_units(); }
  std::string describe() const override;

  // Mean fluid pressure over the footprint at (centre, normal); 0 when dry.
  static double footprint_pressure(const ProbeContext& ctx, const std::vector<int>& fluid_bodies,
                                   const Vec2& centre, const Vec2& normal, const PressureSensor& sensor);

 protected:
  void sample(const ProbeContext& ctx, double* row) override;

 private:
  bool moving_;
  Vec2 centre_;
  MaterialPoint anchor_;
  Vec2 normal_;
  PressureSensor sensor_;
  std::vector<int> fluid_bodies_;
  ReferenceScales scales_;
  std::string where_;
};

}  // namespace bsmpm

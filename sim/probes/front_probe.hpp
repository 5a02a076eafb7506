// Surge front of a fluid body: its furthest extent along a direction, taken as the
// foremost particle centre plus half a particle spacing (Martin & Moyce 1952 measure the
// front from the wall behind the column). Columns t, T*, front [m].
#pragma once

#include <string>
#include <vector>

#include "probes/probe.hpp"

namespace bsmpm {

class FrontProbe final : public Probe {
 public:
  FrontProbe(std::string name, double interval, int body, std::string body_name, Vec2 direction,
             ReferenceScales scales)
      : Probe(std::move(name), interval), body_(body), body_name_(std::move(body_name)),
        direction_(direction.normalized()), scales_(scales) {}

  static std::vector<std::string> column_names() { return {"t", "T*", "front"}; }
  std::vector<std::string> columns() const override { return column_names(); }
  std::vector<std::string> units() const override { return {"s", "1", "m"}; }
  std::string describe() const override;

 protected:
  void sample(const ProbeContext& ctx, double* row) override;

 private:
  int body_;
  std::string body_name_;
  Vec2 direction_;
  ReferenceScales scales_;
};

}  // namespace bsmpm

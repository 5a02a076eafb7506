// A force sensor in a tank wall: the wall's reaction on the water, per length of the
// sensor's face, from the impulse the wall condition gives the control points of that wall
// in the last step (docs/method.md §8, eq. S2). An independent reading of the load that a
// wall_pressure probe takes from the particles next to the wall. Columns t, T*, P, P*.
#pragma once

#include <string>
#include <vector>

#include "probes/probe.hpp"

namespace bsmpm {

class WallReactionProbe final : public Probe {
 public:
  // `share[k]`: the part of control point k's basis function (along the wall) that lies on
  // the face, over its whole integral; `face_length`: the face's length inside the domain.
  WallReactionProbe(std::string name, double interval, int wall, double centre, double face_length,
                    std::vector<double> share, ReferenceScales scales);

  std::vector<std::string> columns() const override;  // a pressure probe's
  std::vector<std::string> units() const override;
  std::string describe() const override;

 protected:
  void sample(const ProbeContext& ctx, double* row) override;

 private:
  int wall_;             // WallSide
  double centre_;        // along the wall [m]
  double face_length_;   // [m]
  std::vector<double> share_;
  ReferenceScales scales_;
};

}  // namespace bsmpm

// One particle's splat (splat_shapes.hpp says what it is and why), built up from what lies
// around the particle: its own layer's neighbours, obstacle particles and the tank's walls,
// added in any order. Offsets are from the particle, in world units.
#pragma once

#include <array>
#include <vector>

#include "core/types.hpp"
#include "paint/splat_shapes.hpp"

namespace bsmpm::render {

// The principal axis (unit) of the neighbours at `offsets` within `radius`, the particle
// itself included: Yu & Turk 2013, eqs. 5-6 (weighted mean and covariance, w = 1 - (d/r)^3).
// It lies along a flat free surface or a chain of particles. Any axis for an isotropic
// neighbourhood (the x axis when there are no neighbours).
Vec2 principal_axis(const std::vector<Vec2>& offsets, const std::vector<double>& distances, double radius);

class SplatBuilder {
 public:
  // `axis`: u_0 (unit), the others turned from it by 45 degrees. `spacing`: the particle's
  // sqrt(volume); `margin`: how far the splat reaches beyond the outermost particles.
  SplatBuilder(const Vec2& axis, double spacing, double margin);

  // A wall of the tank at `distance` (> 0) across its outward unit `normal`: the particle
  // and the neighbours added after this call are mirrored in it (their images within
  // `radius` count as neighbours for the splat's extents).
  void add_wall(const Vec2& normal, double distance, double radius);
  // A neighbour of the particle's own layer at `offset`, `distance` = |offset| > 0.
  void add_neighbour(const Vec2& offset, double distance);
  // A particle of a layer drawn over this one (the splat reaches up to it, not past it).
  void add_obstacle(const Vec2& offset);

  struct Result {
    SplatShape shape;
    // Nothing farther than the `radius` given to finish() can change the shape: every
    // sector is bounded within radius / 2 and no support cuts the splat inside its reach.
    bool settled = false;
  };
  // The shape from everything added so far, all of it within `radius` of the particle.
  Result finish(double radius) const;

 private:
  using Directions = std::array<float, 8>;  // one value per direction u_0 .. u_7
  // The components of d along and across u_0 .. u_7.
  void components(const Vec2& d, Directions& along, Directions& across) const;
  void add_material(const Directions& along, float length);
  void add_image_point(const Vec2& image);
  void add_images(const Vec2& d);

  Vec2 e1_, e2_;
  float spacing_, margin_;
  Directions ahead_;  // furthest point within 45 degrees ahead (beyond that: 0)
  Directions side_;   // cosine of the nearest angle to 45 degrees of a point beyond 45 degrees
  Directions cell_;   // largest 2 cos(22.5 + g) / d (the inverse of a Voronoi bound)
  struct Mirror {
    Vec2 normal;
    double distance, radius;
  };
  std::array<Mirror, 4> walls_{};
  int wall_count_ = 0;
};

}  // namespace bsmpm::render

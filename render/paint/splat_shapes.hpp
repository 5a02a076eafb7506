// The shape of each particle's splat, from where its neighbours are now, so that the
// material is drawn without gaps where the flow has pulled its particles apart and without
// bleeding past its free surface.
//
// Why not a square or disc sized from the volume: in stretched water the particles of an
// MPM run gather in chains along the flow with gaps of 2-5 spacings between the chains,
// while each particle's volume stays that of the intact water. A splat sized from the
// volume leaves the gaps white; one large enough to close them bleeds as far past every
// free surface. A gap and a free surface differ in one way: a gap has particles on its far
// side. So a splat is a disc (its "reach", at most kMaxReach spacings) cut by 8 half-planes,
// p . u_k <= H_k for the offsets p from the particle, u_0 .. u_7 45 degrees apart, where
// H_k is how far the particle's neighbourhood extends along u_k plus a margin of half a
// spacing (times the splat scale): as far as the furthest neighbour within 45 degrees of
// u_k lies along it (across a gap, to its far side), and at least to where the ray along
// u_k leaves the strips of that margin around the segments to the neighbours beyond 45
// degrees (along a row of particles: see splat_builder.cpp). Inside the material every
// direction has neighbours and nothing is cut; at a free surface the outward directions
// have none and the splat ends at the margin, where a seeded block's edge lies (particles
// sit at cell centres, half a spacing inside it).
//
// The directions turn with the neighbourhood where the cuts matter: u_0 is the principal
// axis of the weighted covariance of the neighbours (Yu & Turk 2013, "Reconstructing
// surfaces of particle-based fluids using anisotropic kernels", ACM TOG 32(1), eqs. 5-6),
// which lies along a flat free surface or a chain, so that the surface's normal is one of
// the directions whatever its slope.
//
// The reach bounds the particle's Voronoi cell, sector by sector, so that a point sprite
// no larger than needed is drawn. The painter colours each pixel by the nearest particle
// whose splat holds it (a depth test on the distance): inside intact water each particle
// paints its Voronoi cell, of its own area, and overlapping splats do not smear the
// colour field.
//
// Walls and obstacles: MPM holds particles about a grid cell off a tank wall and off
// another body at a contact. The water is drawn up to them - a wall as a mirror (the images
// of the particle and its neighbours count as neighbours), a particle of a layer drawn over
// the water as a point the splat reaches when it lies straight ahead - and never shows
// past them, since walls and solids are drawn over it.
#pragma once

#include <array>
#include <vector>

#include "core/types.hpp"
#include "image/rect.hpp"

namespace bsmpm::render {

// cos 45 degrees: the turn from one support direction u_k to the next, in the splat builder
// and in the painter's shader.
inline constexpr float kHalfSqrt2 = 0.70710678f;

// No pixel is painted farther than this many spacings (spacing = sqrt(particle volume))
// from its particle: inside the stretched water of the elastic-gate runs (4 and 2 mm,
// t = 0.25-0.4 s) nearly all empty circles between particles (Delaunay circumradii) are
// smaller; larger ones are mostly outside the water. Wider gaps stay open.
inline constexpr double kMaxReach = 2.5;
// Neighbours are searched within this many spacings: the far side of a gap as wide as the
// largest empty circle.
inline constexpr double kNeighbourRadius = 2.0 * kMaxReach;

// What a layer's splats may reach up to besides their own particles (see above).
struct SplatObstacles {
  const WorldRect* walls = nullptr;             // the tank: its inside
  const std::vector<Vec2>* particles = nullptr;  // another layer's particles, drawn over this one
};

// One splat, in world units around its particle (floats: GL vertex attributes).
struct SplatShape {
  float axis_x = 1.0f, axis_y = 0.0f;  // u_0, unit; u_k is u_0 turned by k * 45 degrees
  std::array<float, 8> support{};      // H_k: the splat keeps p with p . u_k <= H_k
  float reach = 0.0f;                  // and |p| <= reach
};

// Shapes of the particles of one layer at `position` (particles of other layers are
// obstacles at most). side[k] is particle k's spacing sqrt(volume); its margin is
// margin_scale * side[k] / 2. Runs on all OpenMP threads; the result does not depend on
// their number. `out` is resized and overwritten.
void compute_splat_shapes(const std::vector<Vec2>& position, const std::vector<double>& side, double margin_scale,
                          const SplatObstacles& obstacles, std::vector<SplatShape>& out);

}  // namespace bsmpm::render

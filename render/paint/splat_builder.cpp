#include "paint/splat_builder.hpp"

#include <algorithm>
#include <cmath>

namespace bsmpm::render {

namespace {

constexpr float kSectorCos = 0.92387953f;  // cos 22.5 degrees: half of 45
constexpr float kSectorSin = 0.38268343f;  // sin 22.5 degrees

// max and min as single instructions (std::fmax would call the library for its NaN rules),
// so that the loops over the 8 directions below run as vector instructions.
inline float larger(float a, float b) { return a > b ? a : b; }
inline float smaller(float a, float b) { return a < b ? a : b; }

}  // namespace

Vec2 principal_axis(const std::vector<Vec2>& offsets, const std::vector<double>& distances, double radius) {
  double weight_sum = 1.0;
  Vec2 mean = Vec2::Zero();
  for (std::size_t j = 0; j < offsets.size(); ++j)
    if (distances[j] < radius) {
      const double q = distances[j] / radius, w = 1.0 - q * q * q;
      weight_sum += w;
      mean += w * offsets[j];
    }
  mean /= weight_sum;
  Mat2 c = mean * mean.transpose();  // the particle itself, at offset 0
  for (std::size_t j = 0; j < offsets.size(); ++j)
    if (distances[j] < radius) {
      const double q = distances[j] / radius, w = 1.0 - q * q * q;
      const Vec2 e = offsets[j] - mean;
      c += w * e * e.transpose();
    }
  // The major axis of a symmetric 2x2 matrix; angle 0 for an isotropic one.
  const double angle = 0.5 * std::atan2(2.0 * c(0, 1), c(0, 0) - c(1, 1));
  return Vec2(std::cos(angle), std::sin(angle));
}

SplatBuilder::SplatBuilder(const Vec2& axis, double spacing, double margin)
    : e1_(axis), e2_(-axis.y(), axis.x()), spacing_(static_cast<float>(spacing)), margin_(static_cast<float>(margin)) {
  ahead_.fill(0.0f);
  side_.fill(0.0f);
  cell_.fill(0.0f);
}

void SplatBuilder::components(const Vec2& d, Directions& along, Directions& across) const {
  const float fx = static_cast<float>(d.dot(e1_)), fy = static_cast<float>(d.dot(e2_));
  const float a = kHalfSqrt2 * (fx + fy), b = kHalfSqrt2 * (fy - fx);
  along = {fx, a, fy, b, -fx, -a, -fy, -b};
  const float fy_abs = std::abs(fy), b_abs = std::abs(b), fx_abs = std::abs(fx), a_abs = std::abs(a);
  across = {fy_abs, b_abs, fx_abs, a_abs, fy_abs, b_abs, fx_abs, a_abs};
}

// How far the splat reaches along u_k, from one point at offset d of the material around
// the particle (a neighbour, or an image in a wall), at angle a from u_k:
//  - when a <= 45 degrees, as far as d lies along u_k, plus the margin: the particle
//    reaches across a gap to material on its far side (and along a row of its neighbours);
//  - when 45 < a < 90 degrees, margin / sin(a): where the ray along u_k leaves the capsule
//    of radius `margin` around the segment from the particle to d. This keeps the splat of
//    a particle at a flat surface as wide as its share of the surface: cut at the margin by
//    the directions at 45 degrees to the surface, it would leave a notch between each two
//    particles. Only the nearest such angle to 45 degrees counts: it is kept as its cosine.
// The splat's extent along u_k is the furthest over all points, and at least the margin
// (the particle's own disc), so a point behind the particle changes nothing.
void SplatBuilder::add_material(const Directions& along, float length) {
  if (!(length > 0.0f)) return;  // a coincident point reaches nowhere
  const float inverse_length = 1.0f / length;
  // On local copies, so that the compiler runs the loop as vector instructions (with
  // -fno-trapping-math: render/CMakeLists.txt).
  Directions ahead = ahead_, side = side_;
  for (int k = 0; k < 8; ++k) {
    const float cosine = along[k] * inverse_length;
    ahead[k] = larger(ahead[k], cosine >= kHalfSqrt2 ? along[k] : 0.0f);
    side[k] = larger(side[k], cosine < kHalfSqrt2 ? cosine : 0.0f);
  }
  ahead_ = ahead;
  side_ = side;
}

// A point of an obstacle counts only when the ray along u_k passes within the margin of
// it, to where the ray leaves the disc of that radius around it: the water reaches up to
// an obstacle straight ahead but does not creep along its face.
void SplatBuilder::add_obstacle(const Vec2& offset) {
  Directions along, across;
  components(offset, along, across);
  const float margin2 = margin_ * margin_;
  Directions ahead = ahead_;
  for (int k = 0; k < 8; ++k) {
    const float room = margin2 - across[k] * across[k];
    ahead[k] = larger(ahead[k], room >= 0.0f ? along[k] + std::sqrt(larger(room, 0.0f)) - margin_ : 0.0f);
  }
  ahead_ = ahead;
}

void SplatBuilder::add_image_point(const Vec2& image) {
  Directions along, across;
  components(image, along, across);
  add_material(along, static_cast<float>(image.norm()));
}

// The images of d in each wall and, behind a corner of two walls, in both.
void SplatBuilder::add_images(const Vec2& d) {
  auto add_image = [&](const Vec2& image, double radius) {
    const double length = image.norm();
    if (length < radius) {
      Directions along, across;
      components(image, along, across);
      add_material(along, static_cast<float>(length));
    }
  };
  auto mirror = [](const Mirror& m, const Vec2& p) { return Vec2(p + 2.0 * (m.distance - p.dot(m.normal)) * m.normal); };
  for (int a = 0; a < wall_count_; ++a) {
    add_image(mirror(walls_[a], d), walls_[a].radius);
    for (int b = a + 1; b < wall_count_; ++b)
      if (std::abs(walls_[a].normal.dot(walls_[b].normal)) < 1e-12)
        add_image(mirror(walls_[b], mirror(walls_[a], d)), std::min(walls_[a].radius, walls_[b].radius));
  }
}

void SplatBuilder::add_wall(const Vec2& normal, double distance, double radius) {
  if (wall_count_ == static_cast<int>(walls_.size()) || !(distance > 0.0) || 2.0 * distance >= radius) return;
  walls_[wall_count_++] = Mirror{normal, distance, radius};
  // The particle's own image, and behind a corner with a wall added before, its image in both.
  add_image_point(2.0 * distance * normal);
  for (int a = 0; a + 1 < wall_count_; ++a)
    if (std::abs(walls_[a].normal.dot(normal)) < 1e-12) {
      const Vec2 corner = 2.0 * walls_[a].distance * walls_[a].normal + 2.0 * distance * normal;
      if (corner.norm() < std::min(radius, walls_[a].radius)) add_image_point(corner);
    }
}

void SplatBuilder::add_neighbour(const Vec2& offset, double distance) {
  if (wall_count_ > 0) add_images(offset);
  if (!(distance > 0.0)) return;  // a coincident neighbour reaches nowhere and bounds no cell
  // What add_material does, and the particle's Voronoi cell in sector k (the points within
  // 22.5 degrees of u_k): a neighbour at angle g from u_k lies within 22.5 + g degrees of
  // every point p of the sector, and p is nearer to the particle than to it only if
  // |p| <= distance / (2 cos(22.5 + g)): a bound when 22.5 + g < 90 degrees. Kept as its
  // inverse, the largest over the neighbours (negative, so ignored, beyond 90 degrees).
  // Written out for u_q and u_(q+4) = -u_q together (the hottest loop of the renderer):
  // along u_(q+4) is minus along u_q, across the same.
  const float fx = static_cast<float>(offset.dot(e1_)), fy = static_cast<float>(offset.dot(e2_));
  const float a = kHalfSqrt2 * (fx + fy), b = kHalfSqrt2 * (fy - fx);
  const std::array<float, 4> along{fx, a, fy, b};
  const std::array<float, 4> across{std::abs(fy), std::abs(b), std::abs(fx), std::abs(a)};
  const float inverse = 1.0f / static_cast<float>(distance), scale = 2.0f * inverse * inverse;
  Directions ahead = ahead_, side = side_, cell = cell_;
  for (int q = 0; q < 4; ++q) {
    const float forward = along[q], backward = -along[q];
    const float cos_forward = forward * inverse, cos_backward = backward * inverse;
    ahead[q] = larger(ahead[q], cos_forward >= kHalfSqrt2 ? forward : 0.0f);
    ahead[q + 4] = larger(ahead[q + 4], cos_backward >= kHalfSqrt2 ? backward : 0.0f);
    side[q] = larger(side[q], cos_forward < kHalfSqrt2 ? cos_forward : 0.0f);
    side[q + 4] = larger(side[q + 4], cos_backward < kHalfSqrt2 ? cos_backward : 0.0f);
    cell[q] = larger(cell[q], scale * (kSectorCos * forward - kSectorSin * across[q]));
    cell[q + 4] = larger(cell[q + 4], scale * (kSectorCos * backward - kSectorSin * across[q]));
  }
  ahead_ = ahead;
  side_ = side;
  cell_ = cell;
}

SplatBuilder::Result SplatBuilder::finish(double radius) const {
  Result out;
  out.shape.axis_x = static_cast<float>(e1_.x());
  out.shape.axis_y = static_cast<float>(e1_.y());
  const float largest_reach = std::max(static_cast<float>(kMaxReach) * spacing_, margin_ / kSectorCos);
  // Reach: a point p of sector k is within the Voronoi bound of the particle if it lies in
  // the particle's cell, and p . u_k <= extent bounds |p| by extent / cos 22.5. The largest
  // over the sectors bounds the splat, so that no larger point sprite than needed is drawn.
  float reach = 0.0f, least_extent = largest_reach, widest_cell = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const float extent = std::max(ahead_[k] + margin_, margin_ / std::sqrt(1.0f - side_[k] * side_[k]));
    const float cell = cell_[k] > 0.0f ? 1.0f / cell_[k] : INFINITY;
    out.shape.support[k] = extent;
    reach = std::max(reach, std::min(cell, extent / kSectorCos));
    least_extent = std::min(least_extent, extent);
    widest_cell = std::max(widest_cell, cell);
  }
  reach = std::min(reach, largest_reach);
  out.shape.reach = reach;
  // A neighbour at distance D bounds no sector more tightly than D / 2, and extents beyond
  // the reach change nothing.
  out.settled = widest_cell <= 0.5f * static_cast<float>(radius) && least_extent >= reach;
  return out;
}

}  // namespace bsmpm::render

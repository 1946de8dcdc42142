// Spherical caps (cones of directions) and their intersections: the solid angle two caps share
// and uniform sampling of it. Caustic photons use them to emit only into the directions that
// both leave a light (a spot's cone, an area light's hemisphere) and reach a specular object.
#pragma once

#include "photon/base/math.h"

namespace photon {

// The directions within `angle` of a unit `axis`; angle >= pi is the whole sphere.
struct Cap {
  Vec3 axis{0.0f, 0.0f, 1.0f};
  double angle = 0.0;  // half angle in radians, in [0, pi]
  float cos_angle = 1.0f;

  Cap() = default;
  Cap(const Vec3& unit_axis, double half_angle);
  static Cap whole_sphere() { return Cap(Vec3(0.0f, 0.0f, 1.0f), kPiD); }
  // The cone from `origin` that just contains the ball (centre, radius); the whole sphere if
  // the origin is inside the ball.
  static Cap towards_ball(const Vec3& origin, const Vec3& center, double radius);

  bool is_whole() const { return angle >= kPiD; }
  double solid_angle() const;
  bool contains(const Vec3& direction) const {
    return is_whole() || dot(direction, axis) >= cos_angle;
  }
  static constexpr double kPiD = 3.14159265358979323846;
};

// Solid angle of caps of half angles t1, t2 whose axes are `beta` apart (Tovchigrechko and
// Vakser 2001, "How common is the funnel-like energy landscape in protein-protein
// interactions?", eq. 4, with the nested, disjoint and complementary cases made explicit).
double cap_overlap(double t1, double t2, double beta);
double cap_overlap(const Cap& a, const Cap& b);

// A direction distributed uniformly over a ∩ b (density 1 / cap_overlap(a, b)). Returns false
// when they share no solid angle. The polar angle about the smaller cap's axis is drawn by
// inverting the overlap of a growing cap with the other (its CDF, in closed form), the azimuth
// uniformly over the arc of that ring inside the other cap.
bool sample_cap_overlap(const Cap& a, const Cap& b, Vec2 u, Vec3* direction);

}  // namespace photon

// Uniform sampling of the solid angle a rectangle subtends from a point (Urena, Fajardo and King
// 2013, "An Area-Preserving Parametrization for Spherical Rectangles"): every direction through
// the rectangle has the density 1 / solid angle, so a point near a large window sees no more
// noise than one far from it (sampling the window's area gives a density that varies as
// distance^2 / cos across it).
#pragma once

#include "photon/base/math.h"

namespace photon {

class SphericalRectangle {
 public:
  // The rectangle `corner` + [0, 1] x `edge_x` + [0, 1] x `edge_y` (the edges at right angles)
  // seen from `origin`. Empty when the point lies in its plane or an edge has no length.
  SphericalRectangle(const Vec3& origin, const Vec3& corner, const Vec3& edge_x,
                     const Vec3& edge_y);

  bool empty() const { return !(solid_angle_ > 0.0); }
  float solid_angle() const { return static_cast<float>(solid_angle_); }
  // The point of the rectangle for `u` in [0, 1)^2; directions towards these points are
  // uniform over the solid angle.
  Vec3 sample(Vec2 u) const;

 private:
  Vec3 origin_, x_, y_, z_;  // z_: the rectangle's normal, towards origin
  double x0_ = 0.0, x1_ = 0.0, y0_ = 0.0, y1_ = 0.0, z0_ = 0.0;  // local extents, z0 < 0
  double b0_ = 0.0, b1_ = 0.0, k_ = 0.0;
  double solid_angle_ = 0.0;
};

}  // namespace photon

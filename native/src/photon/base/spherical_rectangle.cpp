#include "photon/base/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

constexpr double kTwoPiD = 6.28318530717958647692;

struct DVec {
  double x, y, z;
};

DVec unit(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}

// The interior angle between two of the pyramid's side planes (given by their unit normals).
double angle_between(const DVec& a, const DVec& b) {
  return std::acos(std::clamp(-(a.x * b.x + a.y * b.y + a.z * b.z), -1.0, 1.0));
}

}  // namespace

// Section 3 of the paper: the rectangle in a frame at `origin` with x, y along its edges and z
// along its normal, turned so that the rectangle lies at z = z0 < 0.
SphericalRectangle::SphericalRectangle(const Vec3& origin, const Vec3& corner, const Vec3& edge_x,
                                       const Vec3& edge_y)
    : origin_(origin) {
  const double ex = length(edge_x), ey = length(edge_y);
  if (!(ex > 0.0) || !(ey > 0.0) || !std::isfinite(ex) || !std::isfinite(ey)) return;
  x_ = edge_x / static_cast<float>(ex);
  y_ = edge_y / static_cast<float>(ey);
  z_ = cross(x_, y_);
  const Vec3 d = corner - origin;
  x0_ = dot(d, x_);
  y0_ = dot(d, y_);
  z0_ = dot(d, z_);
  if (z0_ > 0.0) {
    z0_ = -z0_;
    z_ = -z_;
  }
  if (!(z0_ < 0.0) || !std::isfinite(x0_) || !std::isfinite(y0_)) return;
  x1_ = x0_ + ex;
  y1_ = y0_ + ey;
  // Normals of the planes through the origin and each edge, inward.
  const DVec n0 = unit(0.0, z0_, -y0_);
  const DVec n1 = unit(-z0_, 0.0, x1_);
  const DVec n2 = unit(0.0, -z0_, y1_);
  const DVec n3 = unit(z0_, 0.0, -x0_);
  const double g0 = angle_between(n0, n1), g1 = angle_between(n1, n2);
  const double g2 = angle_between(n2, n3), g3 = angle_between(n3, n0);
  b0_ = n0.z;
  b1_ = n2.z;
  k_ = kTwoPiD - g2 - g3;
  const double s = g0 + g1 - k_;
  solid_angle_ = std::isfinite(s) && s > 0.0 ? s : 0.0;
}

// Section 4: the solid angle swept from the edge x = x0 is u.x of the whole, which fixes the
// point's x; along the segment at that x, y is placed so the swept part is u.y of it.
Vec3 SphericalRectangle::sample(Vec2 u) const {
  const double au = u.x * solid_angle_ + k_;
  const double fu = (std::cos(au) * b0_ - b1_) / std::sin(au);
  double cu = std::copysign(1.0, fu) / std::sqrt(fu * fu + b0_ * b0_);
  cu = std::clamp(std::isfinite(cu) ? cu : 0.0, -1.0, 1.0);
  double xu = -(cu * z0_) / std::max(std::sqrt(1.0 - cu * cu), 1e-300);
  xu = std::clamp(xu, x0_, x1_);
  const double dist = std::sqrt(xu * xu + z0_ * z0_);
  const double h0 = y0_ / std::sqrt(dist * dist + y0_ * y0_);
  const double h1 = y1_ / std::sqrt(dist * dist + y1_ * y1_);
  const double hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1.0 - 1e-12 ? hv * dist / std::sqrt(1.0 - hv2) : y1_;
  return origin_ + x_ * static_cast<float>(xu) + y_ * static_cast<float>(std::clamp(yv, y0_, y1_)) +
         z_ * static_cast<float>(z0_);
}

}  // namespace photon

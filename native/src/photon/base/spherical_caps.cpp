#include "photon/base/spherical_caps.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

constexpr double kPi_ = Cap::kPiD;

// 2 pi (1 - cos t), written so small caps keep their precision.
double cap_area(double t) {
  const double s = std::sin(0.5 * t);
  return 4.0 * kPi_ * s * s;
}

double safe_acos(double x) {
  return std::acos(std::clamp(x, -1.0, 1.0));
}

// Angle between unit vectors, accurate for small and large angles alike.
double angle_between(const Vec3& a, const Vec3& b) {
  const double cx = double(a.y) * b.z - double(a.z) * b.y;
  const double cy = double(a.z) * b.x - double(a.x) * b.z;
  const double cz = double(a.x) * b.y - double(a.y) * b.x;
  const double d = double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d);
}

// Half-width of the arc of the ring at polar angle t (about the first cap's axis) that lies
// inside a cap of half angle t2 whose axis is beta away.
double arc_half_width(double t, double t2, double beta) {
  const double denom = std::sin(t) * std::sin(beta);
  if (!(denom > 0.0)) return std::cos(beta - t) >= std::cos(t2) ? kPi_ : 0.0;
  return safe_acos((std::cos(t2) - std::cos(t) * std::cos(beta)) / denom);
}

// A uniform direction in the cap (axis, t), in double so small caps stay uniform.
Vec3 sample_cap(const Vec3& axis, double t, Vec2 u) {
  const double one_minus_cos = 2.0 * std::sin(0.5 * t) * std::sin(0.5 * t);
  const double cos_theta = 1.0 - u.x * one_minus_cos;
  const double sin_theta = std::sqrt(std::max(0.0, u.x * one_minus_cos * (1.0 + cos_theta)));
  const double phi = 2.0 * kPi_ * u.y;
  const Frame f(axis);
  return normalize(f.to_world(Vec3(static_cast<float>(sin_theta * std::cos(phi)),
                                   static_cast<float>(sin_theta * std::sin(phi)),
                                   static_cast<float>(cos_theta))));
}

}  // namespace

Cap::Cap(const Vec3& unit_axis, double half_angle)
    : axis(unit_axis),
      angle(std::clamp(half_angle, 0.0, kPiD)),
      cos_angle(static_cast<float>(std::cos(angle))) {}

Cap Cap::towards_ball(const Vec3& origin, const Vec3& center, double radius) {
  const Vec3 to = center - origin;
  const double d = std::sqrt(double(to.x) * to.x + double(to.y) * to.y + double(to.z) * to.z);
  if (!(d > radius)) return whole_sphere();
  return Cap(to / static_cast<float>(d), std::asin(radius / d));
}

double Cap::solid_angle() const {
  return cap_area(angle);
}

double cap_overlap(double t1, double t2, double beta) {
  if (!(t1 > 0.0) || !(t2 > 0.0) || beta >= t1 + t2) return 0.0;
  if (beta + t1 <= t2) return cap_area(t1);
  if (beta + t2 <= t1) return cap_area(t2);
  // The complements are disjoint: together the caps cover the sphere.
  if (t1 + t2 + beta >= 2.0 * kPi_) return cap_area(t1) + cap_area(t2) - 4.0 * kPi_;
  const double c1 = std::cos(t1), c2 = std::cos(t2), s1 = std::sin(t1), s2 = std::sin(t2);
  const double cb = std::cos(beta), sb = std::sin(beta);
  const double area = 2.0 * (kPi_ - safe_acos((cb - c1 * c2) / (s1 * s2)) -
                             c1 * safe_acos((c2 - cb * c1) / (sb * s1)) -
                             c2 * safe_acos((c1 - cb * c2) / (sb * s2)));
  return std::clamp(area, 0.0, std::min(cap_area(t1), cap_area(t2)));
}

double cap_overlap(const Cap& a, const Cap& b) {
  if (a.is_whole()) return b.solid_angle();
  if (b.is_whole()) return a.solid_angle();
  return cap_overlap(a.angle, b.angle, angle_between(a.axis, b.axis));
}

bool sample_cap_overlap(const Cap& cap_a, const Cap& cap_b, Vec2 u, Vec3* direction) {
  // The polar angle is taken about the smaller cap, which bounds it.
  const Cap& a = cap_a.angle <= cap_b.angle ? cap_a : cap_b;
  const Cap& b = cap_a.angle <= cap_b.angle ? cap_b : cap_a;
  if (b.is_whole()) {
    *direction = sample_cap(a.axis, a.angle, u);
    return a.angle > 0.0;
  }
  const double beta = angle_between(a.axis, b.axis);
  const double total = cap_overlap(a.angle, b.angle, beta);
  if (!(total > 0.0)) return false;
  if (beta + a.angle <= b.angle) {
    *direction = sample_cap(a.axis, a.angle, u);
    return true;
  }
  // F(t) = overlap of the cap (a.axis, t) with b grows from 0 at t = beta - b.angle to `total`
  // at t = a.angle with F'(t) = 2 arc(t) sin t: Newton's method kept inside a shrinking bracket.
  const double target = u.x * total;
  double lo = std::max(0.0, beta - b.angle), hi = a.angle;
  double t = 0.5 * (lo + hi);
  for (int i = 0; i < 64; ++i) {
    const double f = cap_overlap(t, b.angle, beta) - target;
    if (std::fabs(f) <= 1e-14 * total) break;
    (f < 0.0 ? lo : hi) = t;
    if (hi - lo <= 1e-15 * a.angle) break;
    const double slope = 2.0 * arc_half_width(t, b.angle, beta) * std::sin(t);
    const double next = slope > 0.0 ? t - f / slope : lo - 1.0;
    t = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  const double phi = (2.0 * u.y - 1.0) * arc_half_width(t, b.angle, beta);
  // Frame: z along a, x towards b.
  const Vec3 z = a.axis;
  Vec3 x = b.axis - z * dot(b.axis, z);
  const float lx = length(x);
  x = lx > 0.0f ? x / lx : Frame(z).t;
  const Vec3 y = cross(z, x);
  const double st = std::sin(t);
  *direction =
      normalize(x * static_cast<float>(st * std::cos(phi)) +
                y * static_cast<float>(st * std::sin(phi)) + z * static_cast<float>(std::cos(t)));
  return true;
}

}  // namespace photon

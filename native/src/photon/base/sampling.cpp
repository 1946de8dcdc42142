#include "photon/base/sampling.h"

namespace photon {

Vec2 sample_concentric_disk(Vec2 u) {
  float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0.0f && oy == 0.0f) return {0.0f, 0.0f};
  float r, theta;
  if (std::fabs(ox) > std::fabs(oy)) {
    r = ox;
    theta = (kPi / 4.0f) * (oy / ox);
  } else {
    r = oy;
    theta = (kPi / 2.0f) - (kPi / 4.0f) * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

Vec2 invert_concentric_disk(Vec2 d) {
  const float r = std::sqrt(d.x * d.x + d.y * d.y);
  if (r == 0.0f) return {0.5f, 0.5f};
  float phi = std::atan2(d.y, d.x);
  if (phi < -kPi / 4.0f) phi += 2.0f * kPi;  // phi in [-pi/4, 7pi/4)
  float a, b;                                // the square point in [-1, 1]^2
  if (phi < kPi / 4.0f) {
    a = r;
    b = phi * (4.0f / kPi) * r;
  } else if (phi < 3.0f * kPi / 4.0f) {
    b = r;
    a = (kPi / 2.0f - phi) * (4.0f / kPi) * r;
  } else if (phi < 5.0f * kPi / 4.0f) {
    a = -r;
    b = -(phi - kPi) * (4.0f / kPi) * r;
  } else {
    b = -r;
    a = -(kPi / 2.0f - (phi - kPi)) * (4.0f / kPi) * r;
  }
  return {std::clamp(0.5f * (a + 1.0f), 0.0f, 0.99999994f),
          std::clamp(0.5f * (b + 1.0f), 0.0f, 0.99999994f)};
}

Vec3 sample_cosine_hemisphere(Vec2 u) {
  Vec2 d = sample_concentric_disk(u);
  float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

Vec3 sample_uniform_sphere(Vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
  float cos_theta = (1.0f - u.x) + u.x * cos_max;
  float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

Vec2 sample_uniform_triangle(Vec2 u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.0f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.0f;
    b0 = u.x - b1;
  }
  return {b0, b1};
}

}  // namespace photon

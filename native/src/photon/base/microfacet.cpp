#include "photon/base/microfacet.h"

namespace photon {

float ggx_d(const Vec3& h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  // alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) = alpha^2 / (pi (sin^2 + alpha^2 cos^2)^2), with
  // sin^2 from the tangential components: 1 - cos^2 would cancel catastrophically near the
  // pole, where a small-alpha lobe lives.
  const float a2 = alpha * alpha;
  const float t = (h.x * h.x + h.y * h.y) + a2 * (h.z * h.z);
  return a2 / (kPi * t * t);
}

float ggx_lambda(const Vec3& w, float alpha) {
  const float c2 = w.z * w.z;
  if (c2 <= 0.0f) return INFINITY;
  const float s2 = w.x * w.x + w.y * w.y;  // not 1 - c2 (cancellation near the pole)
  const float a2_tan2 = alpha * alpha * s2 / c2;
  return 0.5f * (std::sqrt(1.0f + a2_tan2) - 1.0f);
}

float ggx_g1(const Vec3& w, const Vec3& h, float alpha) {
  if (dot(w, h) * w.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + ggx_lambda(w, alpha));
}

float ggx_g2(const Vec3& wo, const Vec3& wi, const Vec3& h, float alpha) {
  return ggx_g1(wo, h, alpha) * ggx_g1(wi, h, alpha);
}

Vec3 ggx_sample_visible_normal(const Vec3& wo, float alpha, Vec2 u) {
  return ggx_sample_visible_normal(wo, alpha, alpha, u);
}

float ggx_visible_normal_pdf(const Vec3& wo, const Vec3& h, float alpha) {
  const float cos_oh = dot(wo, h);
  if (wo.z <= 0.0f || cos_oh <= 0.0f) return 0.0f;
  return ggx_g1(wo, h, alpha) * cos_oh * ggx_d(h, alpha) / wo.z;
}

float ggx_d(const Vec3& h, float ax, float ay) {
  if (h.z <= 0.0f) return 0.0f;
  const float x = h.x / ax, y = h.y / ay;
  const float t = x * x + y * y + h.z * h.z;
  return 1.0f / (kPi * ax * ay * t * t);
}

float ggx_lambda(const Vec3& w, float ax, float ay) {
  const float c2 = w.z * w.z;
  if (c2 <= 0.0f) return INFINITY;
  const float a2_tan2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / c2;
  return 0.5f * (std::sqrt(1.0f + a2_tan2) - 1.0f);
}

float ggx_g1(const Vec3& w, const Vec3& h, float ax, float ay) {
  if (dot(w, h) * w.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + ggx_lambda(w, ax, ay));
}

Vec3 ggx_sample_visible_normal(const Vec3& wo, float ax, float ay, Vec2 u) {
  // Stretch the view direction to the hemisphere configuration (alpha = 1).
  const Vec3 vh = normalize(Vec3(ax * wo.x, ay * wo.y, wo.z));
  // Orthonormal basis around vh (degenerate at normal incidence).
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = cross(vh, t1);
  // Uniform point on the projected disk, warped to the visible half of it.
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  // Reproject onto the hemisphere and unstretch.
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(Vec3(ax * nh.x, ay * nh.y, std::max(1e-7f, nh.z)));
}

float ggx_visible_normal_pdf(const Vec3& wo, const Vec3& h, float ax, float ay) {
  const float cos_oh = dot(wo, h);
  if (wo.z <= 0.0f || cos_oh <= 0.0f) return 0.0f;
  return ggx_g1(wo, h, ax, ay) * cos_oh * ggx_d(h, ax, ay) / wo.z;
}

}  // namespace photon

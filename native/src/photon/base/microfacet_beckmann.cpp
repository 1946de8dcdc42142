#include "photon/base/microfacet_beckmann.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

constexpr float kInvSqrtPi = 0.56418958354775628f;

// a = 1 / (alpha_w tan theta) of direction w: w.z / sqrt(ax^2 wx^2 + ay^2 wy^2); infinite at
// the pole, where every microfacet is visible.
float inverse_slope(const Vec3& w, float ax, float ay) {
  const float s = std::sqrt(ax * ax * w.x * w.x + ay * ay * w.y * w.y);
  return s > 0.0f ? std::fabs(w.z) / s : INFINITY;
}

// The x slope of a visible normal at unit roughness for a view at cos_theta: solves
// F(x) = u with F(x) = (1 + erf(x) + tan e^(-x^2) / sqrt(pi)) / (1 + erf(cot) + tan
// e^(-cot^2) / sqrt(pi)) on x <= cot, in b = erf(x), where dF/db = (1 - x tan) / norm keeps
// Newton's steps well scaled; a bisection bracket catches the steps that leave it.
float sample_visible_slope_x(float cos_theta, float u) {
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float tan_theta = sin_theta / cos_theta;
  const float cot_theta = cos_theta / sin_theta;
  float lo = -1.0f;
  float hi = std::erf(cot_theta);
  u = std::max(u, 1e-6f);
  const float norm = 1.0f / (1.0f + hi + kInvSqrtPi * tan_theta * std::exp(-cot_theta * cot_theta));
  // A fitted first guess (Jakob's, from Mitsuba) that leaves a few Newton steps.
  const float theta = std::acos(cos_theta);
  const float fit = 1.0f + theta * (-0.876f + theta * (0.4265f - 0.0594f * theta));
  float b = hi - (1.0f + hi) * std::pow(1.0f - u, fit);
  for (int it = 0; it < 10; ++it) {
    if (!(b >= lo && b <= hi)) b = 0.5f * (lo + hi);
    const float x = erf_inverse(b);
    const float value = norm * (1.0f + b + kInvSqrtPi * tan_theta * std::exp(-x * x)) - u;
    if (std::fabs(value) < 1e-5f) break;
    if (value > 0.0f) {
      hi = b;
    } else {
      lo = b;
    }
    b -= value / (norm * (1.0f - x * tan_theta));
  }
  if (!(b >= lo && b <= hi)) b = 0.5f * (lo + hi);
  return erf_inverse(b);
}

}  // namespace

float erf_inverse(float x) {
  x = std::clamp(x, -0.99999994f, 0.99999994f);
  float w = -std::log((1.0f - x) * (1.0f + x));
  float p;
  if (w < 5.0f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

float beckmann_d(const Vec3& h, float ax, float ay) {
  if (h.z <= 0.0f) return 0.0f;
  const float x = h.x / ax, y = h.y / ay;
  const float c2 = h.z * h.z;
  return std::exp(-(x * x + y * y) / c2) / (kPi * ax * ay * c2 * c2);
}

float beckmann_lambda(const Vec3& w, float ax, float ay) {
  if (w.z == 0.0f) return INFINITY;
  const float a = inverse_slope(w, ax, ay);
  if (a > 9.0f) return 0.0f;  // below float's resolution of 1
  // erf(a) - 1 = -erfc(a), without the cancellation.
  return 0.5f * (kInvSqrtPi * std::exp(-a * a) / a - std::erfc(a));
}

float beckmann_lambda_approx(const Vec3& w, float ax, float ay) {
  if (w.z == 0.0f) return INFINITY;
  const float a = inverse_slope(w, ax, ay);
  if (a >= 1.6f) return 0.0f;
  return (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
}

float beckmann_g1(const Vec3& w, const Vec3& h, float ax, float ay) {
  if (dot(w, h) * w.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + beckmann_lambda_approx(w, ax, ay));
}

Vec3 beckmann_sample_visible_normal(const Vec3& wo, float ax, float ay, Vec2 u) {
  // Stretch the view to unit roughness.
  const Vec3 v = normalize(Vec3(ax * wo.x, ay * wo.y, std::max(wo.z, 1e-7f)));
  float sx, sy;
  if (v.z > 0.9999f) {
    // Seen from the pole every normal is visible: the slopes are a 2D Gaussian.
    const float r = std::sqrt(-std::log(std::max(1.0f - u.x, 1e-12f)));
    const float phi = 2.0f * kPi * u.y;
    sx = r * std::cos(phi);
    sy = r * std::sin(phi);
  } else {
    sx = sample_visible_slope_x(v.z, u.x);
    sy = erf_inverse(2.0f * std::max(u.y, 1e-6f) - 1.0f);
    // Rotate from the view's azimuth to the frame's.
    const float len = std::sqrt(v.x * v.x + v.y * v.y);
    const float cos_phi = v.x / len, sin_phi = v.y / len;
    const float rx = cos_phi * sx - sin_phi * sy;
    sy = sin_phi * sx + cos_phi * sy;
    sx = rx;
  }
  // Unstretch; the normal of slopes (sx, sy) is (-sx, -sy, 1).
  return normalize(Vec3(-ax * sx, -ay * sy, 1.0f));
}

float beckmann_visible_normal_pdf(const Vec3& wo, const Vec3& h, float ax, float ay) {
  const float cos_oh = dot(wo, h);
  if (wo.z <= 0.0f || cos_oh <= 0.0f) return 0.0f;
  return cos_oh * beckmann_d(h, ax, ay) / ((1.0f + beckmann_lambda(wo, ax, ay)) * wo.z);
}

}  // namespace photon

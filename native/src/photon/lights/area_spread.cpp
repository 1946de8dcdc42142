#include "photon/lights/area_spread.h"

#include <algorithm>
#include <cmath>

namespace photon {

AreaSpread::AreaSpread(float spread) {
  // Cycles treats a spread within a hair of 180 degrees as none; anything at or above pi (or
  // NaN) is the Lambertian lamp.
  if (!(spread < kPi - 1e-4f)) return;
  active_ = true;
  half_ = 0.5f * std::max(spread, kMinSpread);
  const double h = half_, t = std::tan(h);
  tan_half_ = static_cast<float>(t);
  // tan h - h loses its digits to cancellation for small h: use its series h^3 / 3 + 2 h^5 / 15
  // there (error below 1e-7 relative for h < 0.05).
  const double excess = h > 0.05 ? t - h : h * h * h * (1.0 / 3.0 + 2.0 / 15.0 * h * h);
  normalize_ = static_cast<float>(1.0 / excess);
}

float AreaSpread::attenuation(float cos_theta) const {
  if (!active_) return 1.0f;
  if (!(cos_theta > 0.0f)) return 0.0f;
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return std::max(tan_half_ - sin_theta / cos_theta, 0.0f) * normalize_;
}

Vec3 AreaSpread::sample_direction(Vec2 u) const {
  // With t = tan theta, the density cos * a / pi over solid angle gives theta the cumulative
  // distribution F(t) = [T t^2 / (1 + t^2) + t / (1 + t^2) - atan t] / (T - h), T = tan h,
  // whose derivative is 2 t (T - t) / ((1 + t^2)^2 (T - h)). Solve F(t) = u by Newton steps
  // kept inside a shrinking bracket [lo, hi] (F is increasing on [0, T]); in double, since
  // F's numerator is a difference of nearly equal terms for narrow spreads.
  const double big_t = tan_half_;
  const double excess = 1.0 / static_cast<double>(normalize_);
  const double target = std::clamp(static_cast<double>(u.x), 0.0, 1.0);
  auto cdf = [&](double t) {
    const double q = 1.0 + t * t;
    return (big_t * t * t / q + t / q - std::atan(t)) / excess;
  };
  double lo = 0.0, hi = big_t, t = big_t * std::sqrt(target);  // a start near the solution
  for (int i = 0; i < 60; ++i) {
    const double f = cdf(t) - target;
    if (f > 0.0)
      hi = t;
    else
      lo = t;
    const double q = 1.0 + t * t;
    const double slope = 2.0 * t * (big_t - t) / (q * q * excess);
    double next = slope > 0.0 ? t - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - t) <= 1e-12 * big_t) {
      t = next;
      break;
    }
    t = next;
  }
  const double cos_theta = 1.0 / std::sqrt(1.0 + t * t), sin_theta = t * cos_theta;
  const double phi = 6.283185307179586 * u.y;
  return Vec3(static_cast<float>(sin_theta * std::cos(phi)),
              static_cast<float>(sin_theta * std::sin(phi)), static_cast<float>(cos_theta));
}

}  // namespace photon

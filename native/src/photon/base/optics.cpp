#include "photon/base/optics.h"

namespace photon {

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = std::sqrt(1.0f - sin2_t);
  // Hecht, Optics, eqs. 4.34 and 4.35 (s- and p-polarised amplitudes).
  float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt) {
  float cos_i = dot(n, wi);
  float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  float cos_t = std::sqrt(1.0f - sin2_t);
  *wt = normalize(-wi / eta + n * (cos_i / eta - cos_t));
  return true;
}

}  // namespace photon

#include "photon/lights/lights.h"

namespace photon {

LightSet::LightSet(const std::vector<Light>& lights, std::vector<std::string>* warnings) {
  IesCache ies_profiles;
  for (const Light& l : lights)
    if (std::unique_ptr<Lamp> lamp = make_lamp(l, warnings, &ies_profiles))
      lamps_.push_back(std::move(lamp));
}

bool LightSet::intersect(const Ray& ray, float tmax, uint32_t mask, float* t_hit, Vec3* radiance,
                         size_t* index) const {
  bool found = false;
  float best = tmax;
  for (size_t i = 0; i < lamps_.size(); ++i)
    if (intersect_one(i, ray, best, mask, &best, radiance)) {
      found = true;
      if (index) *index = i;
    }
  if (found) *t_hit = best;
  return found;
}

bool LightSet::intersect_one(size_t index, const Ray& ray, float tmax, uint32_t mask, float* t_hit,
                             Vec3* radiance) const {
  const Lamp& lamp = *lamps_[index];
  if (!(lamp.visibility() & mask)) return false;
  LightHit hit;
  if (!lamp.intersect(ray, tmax, false, &hit)) return false;
  *t_hit = hit.distance;
  *radiance = hit.radiance;
  return true;
}

Vec3 LightSet::distant_radiance(const Vec3& direction, uint32_t mask) const {
  Vec3 sum(0.0f);
  for (const std::unique_ptr<Lamp>& lamp : lamps_) {
    if (!(lamp->flags() & kEmitterInfinite) || !(lamp->visibility() & mask)) continue;
    const Vec3 l = lamp->radiance_at_infinity(direction, false);
    if (!is_black(l)) sum += l;
  }
  return sum;
}

SampledSpectrum LightSet::distant_radiance(const Vec3& direction, uint32_t mask,
                                           const SampledWavelengths& wl) const {
  SampledSpectrum sum(0.0f);
  for (const std::unique_ptr<Lamp>& lamp : lamps_) {
    if (!(lamp->flags() & kEmitterInfinite) || !(lamp->visibility() & mask)) continue;
    const Vec3 l = lamp->radiance_at_infinity(direction, false);
    if (!is_black(l)) sum += lamp->spectrum(l, wl);
  }
  return sum;
}

}  // namespace photon

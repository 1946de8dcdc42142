// The lamps of a scene (lamp.h, one class per kind), in scene order, and what rays meet of them:
// the nearest lamp surface along a ray (camera and glossy rays see lamps with a size), and the
// suns' discs seen by rays that leave the scene.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "photon/lights/lamp.h"

namespace photon {

class LightSet {
 public:
  // The scene's lights as lamps; lights that cannot render (non-finite, zero power or size)
  // are left out, with a warning where the user should know.
  explicit LightSet(const std::vector<Light>& lights, std::vector<std::string>* warnings);

  size_t size() const { return lamps_.size(); }
  const Lamp& lamp(size_t index) const { return *lamps_[index]; }

  // Nearest lamp surface (area quad/disc or point-lamp sphere) hit by the ray before `tmax`
  // among lamps whose visibility matches `mask`. Returns the emitted radiance towards the ray
  // and, when `index` is given, the lamp's index.
  bool intersect(const Ray& ray, float tmax, uint32_t mask, float* t_hit, Vec3* radiance,
                 size_t* index = nullptr) const;
  // The same for lamp `index` alone.
  bool intersect_one(size_t index, const Ray& ray, float tmax, uint32_t mask, float* t_hit,
                     Vec3* radiance) const;

  // Radiance from lamps at infinity (sun discs) along a ray that left the scene, for lamps
  // whose visibility matches `mask`. Zero when the direction misses every sun.
  Vec3 distant_radiance(const Vec3& direction, uint32_t mask) const;
  // The same at the wavelengths, each sun's light at its own spectrum.
  SampledSpectrum distant_radiance(const Vec3& direction, uint32_t mask,
                                   const SampledWavelengths& wl) const;
  // Spectral mode: what lamp `index` emits at the wavelengths, given a value `rgb` it returned.
  SampledSpectrum spectrum(size_t index, const Vec3& rgb, const SampledWavelengths& wl) const {
    return lamps_[index]->spectrum(rgb, wl);
  }

 private:
  std::vector<std::unique_ptr<Lamp>> lamps_;
};

}  // namespace photon

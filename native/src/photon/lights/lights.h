// Light sources in world space, in the units Cycles gives Blender's lights, so an artist's watts
// mean the same in both engines:
//  - point / spot of power P: radiant intensity I = P / (4 pi) W/sr (spot: times Cycles' cone
//    attenuation); with a radius r they are a disc of radius r facing the shaded point;
//  - sun of strength S: irradiance S W/m^2 on a surface facing it, spread over its angular disc;
//  - area of power P and area A: one-sided, uniform radiance L = P / (4 A) (Cycles' eval_fac of
//    0.25 / A), emitted down the light's local -Z axis.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "photon/base/math.h"
#include "photon/base/spherical_caps.h"
#include "photon/lights/emission_pdf.h"
#include "photon/lights/light_bounds.h"
#include "photon/scene/scene.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {

class Emitter;

// A sampled connection from a shading point to a light.
struct LightSample {
  Vec3 wi;           // unit direction from the shading point towards the light
  float distance;    // to the sampled point; INFINITY for the sun
  Vec3 weight;       // Le * G / pdf without the receiver cosine: irradiance per unit cos(theta)
  float pdf = 0.0f;  // solid-angle density of wi; 0 for delta lights (point, spot, sun)
  // Geometric normal at the sampled point when it lies on scene geometry (an emissive
  // triangle), so the shadow ray can stop short of that surface; zero for lamps, which are
  // not in the BVH.
  Vec3 surface_normal{0.0f};
};

// A photon leaving a light: its ray and its flux before dividing by the number of photons
// and the probability of having picked this light.
struct EmittedPhoton {
  Ray ray;
  Vec3 power;
  // The emitter it left (set by PhotonSources), whose spectrum it carries in spectral mode.
  const Emitter* emitter = nullptr;
};

// Spheres around the specular objects that caustic photons are aimed at.
struct BoundingSphere {
  Vec3 center;
  float radius = 0.0f;
};

class LightSet {
 public:
  explicit LightSet(const std::vector<Light>& lights, std::vector<std::string>* warnings);

  size_t size() const { return lights_.size(); }

  // Samples light `index` as seen from point `p`. Returns false if it sends nothing there.
  bool sample(size_t index, const Vec3& p, Vec2 u, LightSample* out) const;

  // Nearest light surface (area quad/disc or point-light sphere) hit by the ray before `tmax`
  // among lights whose visibility matches `mask`. Returns the emitted radiance towards the ray
  // and, when `index` is given, the light's index.
  bool intersect(const Ray& ray, float tmax, uint32_t mask, float* t_hit, Vec3* radiance,
                 size_t* index = nullptr) const;
  // The same for light `index` alone.
  bool intersect_one(size_t index, const Ray& ray, float tmax, uint32_t mask, float* t_hit,
                     Vec3* radiance) const;

  // Radiance from lights at infinity (sun discs) along a ray that left the scene, for lights
  // whose visibility matches `mask`. Zero when the direction misses every sun.
  Vec3 distant_radiance(const Vec3& direction, uint32_t mask) const;

  // Spectral mode: what light `index` emits at the wavelengths, given a value `rgb` it returned
  // (its radiance, intensity, flux or a sample weight, all multiples of its colour): its
  // spectrum scaled to that value's luminance, or its colour's illuminant uplift scaled alike.
  SampledSpectrum spectrum(size_t index, const Vec3& rgb, const SampledWavelengths& wl) const;
  // distant_radiance at the wavelengths.
  SampledSpectrum distant_radiance(const Vec3& direction, uint32_t mask,
                                   const SampledWavelengths& wl) const;

  // For multiple importance sampling: whether sample() of this light has a density (area
  // lights, point and spot lights with a radius), and the radiance, distance and solid-angle
  // density sample() would produce for direction `wi` from `p` (false if it misses the light).
  bool has_area(size_t index) const;
  bool eval(size_t index, const Vec3& p, const Vec3& wi, Vec3* radiance, float* distance,
            float* pdf) const;

  // Photon emission (light_emission.cpp). `scene_center` / `scene_radius` bound the scene,
  // for the sun's beam. power(): the light's emitted flux in W per channel.
  Vec3 power(size_t index, float scene_radius) const;
  void emit(size_t index, const Vec3& scene_center, float scene_radius, Vec2 u_pos, Vec2 u_dir,
            EmittedPhoton* out) const;
  // Caustic photons: directions restricted to the overlap of the light's emission with cones
  // around `targets` (Jensen's projection maps in continuous form); the photon's power carries
  // the correction, so the caustic's expected flux is the light's own. `coverage()` is the
  // fraction of the light's flux heading to the targets, for splitting photons between lights.
  bool emit_towards(size_t index, const std::vector<BoundingSphere>& targets,
                    const Vec3& scene_center, float scene_radius, float u_pick, Vec2 u_pos,
                    Vec2 u_dir, EmittedPhoton* out) const;
  float coverage(size_t index, const std::vector<BoundingSphere>& targets,
                 float scene_radius) const;

  // Bidirectional estimators (emitter.h, EmissionSample; lamp_vcm.cpp). Lamps with a radius
  // are Lambertian spheres there (their emitted rays and light samples both start on the
  // sphere, so every strategy has a density for every path); a sun of angle 0 is a parallel
  // beam.
  uint8_t vcm_flags(size_t index) const;
  bool emit_vcm(size_t index, const Vec3& scene_center, float scene_radius, Vec2 u_pos, Vec2 u_dir,
                EmissionSample* out) const;
  bool illuminate_vcm(size_t index, float scene_radius, const Vec3& p, Vec2 u,
                      Illumination* out) const;
  bool hit_vcm(size_t index, float scene_radius, const Ray& ray, float tmax, EmitterHit* out) const;

  // Where light `index` is and which way it shines, for the light tree (emitters.cpp); power is
  // left for the caller to fill in. Suns are `infinite`.
  LightBounds bounds(size_t index) const;

 private:
  struct Prepared {
    LightType type;
    AreaShape shape;
    uint32_t visibility;
    Vec3 position;
    Vec3 axis;            // emission direction (world -Z of the light), unit
    Vec3 half_u, half_v;  // area: half extents in world space
    Vec3 intensity;       // point / spot: W/sr
    Vec3 radiance;        // area, sphere and sun surfaces: W/m^2/sr
    Vec3 irradiance;      // sun: W/m^2
    float radius;
    float area;
    float cos_half_spot;
    float spot_smooth;
    float sun_cos_max;  // cos of half the sun's angular diameter
  };
  // A point or spot with a radius, which bidirectional estimators treat as a sphere; the
  // direction density of its emitted rays, and its radiance along a direction of travel d.
  static bool sphere_lamp(const Prepared& l);
  static float lamp_direction_pdf(const Prepared& l, const Vec3& d);
  static Vec3 sphere_radiance(const Prepared& l, const Vec3& d);
  // A light's spectrum: a tabulated shape of luminance 1, or its colour uplifted once.
  struct Spectrum {
    const spectral::TabulatedSpectrum* shape = nullptr;
    std::optional<spectral::RgbIlluminantSpectrum> uplift;
    float inv_luminance = 0.0f;  // 1 / luminance of the colour the uplift was made from
  };
  static float spot_attenuation(const Prepared& l, const Vec3& dir_from_light);
  static Cap emission_region(const Prepared& l);
  std::vector<Prepared> lights_;
  std::vector<Spectrum> spectra_;                                           // one per light
  std::vector<std::shared_ptr<const spectral::TabulatedSpectrum>> shapes_;  // blackbodies
};

}  // namespace photon

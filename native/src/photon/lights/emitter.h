// One interface for everything that emits light: Blender's lamps, emissive triangles (one by one
// for the light tree, or all of them as one power-sampled group) and the constant world. Direct
// lighting and photon emission go through it, so a new kind of light (an HDRI environment) is
// one more Emitter.
#pragma once

#include <vector>

#include "photon/base/math.h"
#include "photon/base/rng.h"
#include "photon/lights/light_bounds.h"
#include "photon/lights/lights.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon {

// How a BSDF-sampled ray finds an emitter, for multiple importance sampling (Veach 1997):
enum class EmitterKind : uint8_t {
  kLamp,     // analytic, not in the BVH: eval() intersects it
  kSurface,  // scene geometry: the ray's hit is looked up with surface_pdf()
  kWorld,    // at infinity, reached by rays that leave the scene; a uniform world is sampled
             // through the BSDF only, an environment map also by sample() (environment.h)
};

// Scene extent for photon emission from lights at infinity.
struct PhotonFrame {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

class Emitter {
 public:
  virtual ~Emitter() = default;
  virtual EmitterKind kind() const = 0;

  // Light sampling towards `p`: draws its random numbers from `sampler` (a lamp or a triangle
  // one 2D sample, the emissive group a 1D pick and a 2D point, the world none). False if it
  // sends nothing to p (or, for the world, never: it is sampled through the BSDF).
  virtual bool sample(const Vec3& p, Sampler& sampler, LightSample* out) const = 0;
  // Whether a BSDF-sampled ray can hit it, so the light sample is weighted against it.
  virtual bool has_area() const = 0;
  // kLamp: radiance, distance and the solid-angle density sample() gives direction `wi` from p.
  virtual bool eval(const Vec3& /*p*/, const Vec3& /*wi*/, Vec3* /*radiance*/, float* /*distance*/,
                    float* /*pdf*/) const {
    return false;
  }
  // kSurface: sample()'s solid-angle density for the triangle (Embree instance / primitive)
  // hit at `distance` with cosine `cos_light` to its normal; 0 if that triangle is not this one.
  virtual float surface_pdf(uint32_t /*instance*/, uint32_t /*primitive*/, float /*distance*/,
                            float /*cos_light*/) const {
    return 0.0f;
  }
  // kWorld: radiance arriving along a ray that left the scene.
  virtual Vec3 radiance_at_infinity(const Vec3& /*direction*/) const { return Vec3(0.0f); }
  // kWorld: whether sample() draws directions (an environment map), so direct lighting weights
  // it against BSDF samples by MIS; false for a uniform world, reached through the BSDF only.
  virtual bool sampled_at_infinity() const { return false; }
  // kWorld: sample()'s solid-angle density of `direction` (0 when not sampled_at_infinity()).
  virtual float pdf_at_infinity(const Vec3& /*direction*/) const { return 0.0f; }

  // Spectral mode: what this emitter sends at the wavelengths, given any value `rgb` it
  // returned (radiance, a light sample's weight, flux: non-negative multiples of its colour at
  // that point). By default the colour uplifted as an illuminant; lamps use their spectrum.
  virtual SampledSpectrum spectrum(const Vec3& rgb, const SampledWavelengths& wl) const {
    return spectral::illuminant_at(rgb, wl);
  }

  // Photon emission (Jensen 2001 sec. 5.1). power(): emitted flux, W per channel.
  virtual Vec3 power(float scene_radius) const = 0;
  // A photon with the flux it carries if it were the only one. `u_rest` is the random number
  // left over from picking this emitter (the group picks a triangle with it).
  virtual void emit(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
                    EmittedPhoton* out) const = 0;
  // Caustic photons aimed at `targets`, and the share of the flux heading to them.
  virtual bool emit_towards(const std::vector<BoundingSphere>& /*targets*/,
                            const PhotonFrame& /*frame*/, float /*u_pick*/, Vec2 /*u_pos*/,
                            Vec2 /*u_dir*/, Sampler& /*sampler*/, EmittedPhoton* /*out*/) const {
    return false;
  }
  virtual float coverage(const std::vector<BoundingSphere>& /*targets*/,
                         float /*scene_radius*/) const {
    return 0.0f;
  }

  // For the light tree.
  virtual LightBounds bounds() const = 0;

  // Bidirectional estimators (see EmissionSample). The defaults support nothing; no existing
  // estimator calls these, so adding them changes no image.
  virtual uint8_t vcm_flags() const { return 0; }
  virtual bool emit_vcm(const PhotonFrame& /*frame*/, float /*u_rest*/, Vec2 /*u_pos*/,
                        Vec2 /*u_dir*/, EmissionSample* /*out*/) const {
    return false;
  }
  virtual bool illuminate_vcm(const PhotonFrame& /*frame*/, const Vec3& /*p*/, float /*u_rest*/,
                              Vec2 /*u*/, Illumination* /*out*/) const {
    return false;
  }
  // kLamp: the emitter's surface met by `ray` before `tmax`; kWorld and lamps at infinity: the
  // radiance along a ray that left the scene (tmax INFINITY).
  virtual bool hit_vcm(const PhotonFrame& /*frame*/, const Ray& /*ray*/, float /*tmax*/,
                       EmitterHit* /*out*/) const {
    return false;
  }
  // kSurface: densities for the triangle (Embree instance / primitive) hit with cosine
  // `cos_light` to its normal; false if that triangle is not this emitter's. The radiance is
  // the caller's (the shaded emission).
  virtual bool surface_hit_vcm(uint32_t /*instance*/, uint32_t /*primitive*/, float /*cos_light*/,
                               EmitterHit* /*out*/) const {
    return false;
  }
};

}  // namespace photon

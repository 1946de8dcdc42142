// The one light interface (pbrt-v4's Light: SampleLi, PDF_Li and L, SampleLe, PDF_Le, Phi,
// Bounds), for everything that emits: Blender's lamps (lamp.h), emissive triangles alone or as
// one power-sampled group (emissive_lights.h), the uniform world (world_light.h) and an
// environment (environment.h). Direct lighting, photon emission and the bidirectional estimators
// (VCM) all go through it; each kind of light is written once, in its own file.
//
// Bidirectional estimators (vertex connection and merging, Georgiev et al. 2012; the MIS
// quantities of Davidovic et al. 2012) weigh a path by the densities of every technique that
// could have made it, so besides sampling they need, per light: the density of an emitted ray
// (position in area measure, direction in solid angle), the density of a light sample towards a
// point, and both densities for a point a camera ray met. As in SmallVCM, lights return these
// only on request (`bidirectional`): unidirectional estimators never pay for them. A light may
// then sample with a technique whose densities every strategy shares: a lamp with a radius is
// the sphere camera rays meet rather than the disc facing the receiver that direct lighting
// samples (Cycles 3.x). Lights at infinity measure "position" on the disc across the direction
// that covers the scene (PhotonFrame); delta positions and directions count as probability 1.
#pragma once

#include <cstdint>
#include <vector>

#include "photon/base/math.h"
#include "photon/base/rng.h"
#include "photon/lights/light_bounds.h"
#include "photon/spectral/rgb_uplift.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon {

// How a ray that was not aimed at an emitter finds it, for multiple importance sampling:
enum class EmitterKind : uint8_t {
  kLamp,     // analytic, not in the BVH: intersect() and eval_li() find it
  kSurface,  // scene geometry: the ray's hit is looked up with surface_hit()
  kWorld,    // at infinity, reached by rays that leave the scene (radiance_at_infinity)
};

// What an emitter is, for estimators that weigh its samples against other strategies.
enum EmitterFlags : uint8_t {
  kEmitterBidirectional = 1u << 0,   // gives bidirectional densities
  kEmitterDeltaPosition = 1u << 1,   // a point: camera rays never meet it
  kEmitterDeltaDirection = 1u << 2,  // a parallel beam (sun of angle 0)
  kEmitterInfinite = 1u << 3,        // at infinity: sun, world
  // Direct lighting reaches it by BSDF sampling only (the uniform world): sample_li() draws
  // nothing for it without bidirectional densities.
  kEmitterBsdfSampledOnly = 1u << 4,
};

// Scene extent for emission from lights at infinity.
struct PhotonFrame {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

// Spheres around the specular objects that caustic photons are aimed at.
struct BoundingSphere {
  Vec3 center;
  float radius = 0.0f;
};

// The random numbers of a light sample towards a point: `pick` is what is left of the number
// that picked the emitter (an emissive group picks its triangle with it), `uv` a 2D sample.
struct LightSampleU {
  float pick = 0.0f;
  Vec2 uv{0.0f, 0.0f};
};

// A light sample towards a receiving point.
struct LightSample {
  Vec3 wi{0.0f};          // unit direction from the receiver towards the light
  float distance = 0.0f;  // to the sampled point; INFINITY for lights at infinity
  Vec3 weight{0.0f};      // Le * G / pdf without the receiver cosine: irradiance per unit cos
  float pdf = 0.0f;       // solid-angle density of wi; 0 for delta lights (point, spot, sun)
  // Geometric normal at the sampled point when it lies on scene geometry (an emissive
  // triangle), so the shadow ray can stop short of that surface; zero for lamps.
  Vec3 surface_normal{0.0f};
  // Bidirectional densities, filled on request:
  Vec3 radiance{0.0f};        // Le towards the receiver: W/m^2/sr; a point W/sr; a beam W/m^2
  float direct_pdf = 0.0f;    // density of wi in the measure above (delta position: distance^2,
                              // so radiance / direct_pdf is the irradiance; delta direction: 1)
  float emission_pdf = 0.0f;  // pdf_pos * pdf_dir of sample_le() making the reverse ray
  float cos_light = 1.0f;     // |cos| at the light's surface (1: none)
};

// What a ray meets of an emitter: radiance and how else that point could be sampled.
struct LightHit {
  Vec3 radiance{0.0f};
  float distance = INFINITY;
  float pdf = 0.0f;  // the light sample's solid-angle density of this direction (direct lighting)
  // Bidirectional densities, filled on request:
  float direct_pdf = 0.0f;    // sample_li's density: area measure, or solid angle at infinity
  float emission_pdf = 0.0f;  // sample_le's pdf_pos * pdf_dir for the reverse ray
  float cos_light = 1.0f;     // |cos| of the ray to the emitting surface (1: at infinity)
};

// A ray leaving an emitter: a photon, or the first vertex of a light subpath.
struct EmittedPhoton {
  Ray ray;
  // The flux it carries if it were the only one (photons; not filled for bidirectional
  // requests).
  Vec3 power{0.0f};
  // The emitter it left (set by PhotonSources), whose spectrum it carries in spectral mode.
  const class Emitter* emitter = nullptr;
  // Bidirectional densities, filled on request:
  Vec3 radiance{0.0f};      // Le along the ray: W/m^2/sr; a point W/sr; a delta direction W/m^2
  float pdf_pos = 0.0f;     // area density of the origin (1: delta position)
  float pdf_dir = 0.0f;     // solid-angle density of the direction (1: delta direction)
  float cos_light = 1.0f;   // |cos| of the direction to the emitting surface (1: none)
  float direct_pdf = 0.0f;  // density of sample_li() picking this origin: area measure
                            // (finite), solid angle (infinite), 1 for delta emitters
};

class Emitter {
 public:
  virtual ~Emitter() = default;
  virtual EmitterKind kind() const = 0;
  virtual uint8_t flags() const = 0;  // EmitterFlags
  // For the light tree: where it is, which way it shines, its power.
  virtual LightBounds bounds() const = 0;
  // Emitted flux, W per channel (lights at infinity: through the disc covering the scene).
  virtual Vec3 power(float scene_radius) const = 0;
  // Spectral mode: what it sends at the wavelengths, given any value `rgb` it returned
  // (radiance, a light sample's weight, flux: non-negative multiples of its colour at that
  // point). By default the colour uplifted as an illuminant; lamps use their spectrum.
  virtual SampledSpectrum spectrum(const Vec3& rgb, const SampledWavelengths& wl) const {
    return spectral::illuminant_at(rgb, wl);
  }

  // --- Light towards a point (direct lighting; connections to lights) ---
  // The random numbers a light sample for direct lighting takes from `sampler`: a 2D sample by
  // default, also a pick for emitters that choose among parts (the emissive group), none for
  // one that is not light-sampled there (the uniform world).
  virtual LightSampleU draw_li(Sampler& sampler) const {
    LightSampleU u;
    u.uv = sampler.get_2d();
    return u;
  }
  // A light sample towards `p`; false if the light sends nothing there. Without
  // `bidirectional`, `out`'s weight and pdf; with it (the scene's extent, for lights at
  // infinity), its radiance and densities.
  virtual bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                         LightSample* out) const = 0;
  // Whether a BSDF-sampled ray can hit it, so the light sample is weighted against it.
  virtual bool has_area() const = 0;
  // kLamp: the surface sample_li() (without bidirectional) draws from, met from `p` along
  // `wi`: radiance, distance and its solid-angle density (for MIS).
  virtual bool eval_li(const Vec3& /*p*/, const Vec3& /*wi*/, LightHit* /*out*/) const {
    return false;
  }

  // --- What a ray meets ---
  // kLamp: the emitter's surface met by `ray` before `tmax` (camera and glossy rays; with
  // `bidirectional`, only its outside, with densities).
  virtual bool intersect(const Ray& /*ray*/, float /*tmax*/, bool /*bidirectional*/,
                         LightHit* /*out*/) const {
    return false;
  }
  // kSurface: the densities for the triangle (Embree instance / primitive) a ray hit at
  // `distance` with cosine `cos_light` to its normal; false if that triangle is not this
  // emitter's. The radiance is the caller's (the shaded emission).
  virtual bool surface_hit(uint32_t /*instance*/, uint32_t /*primitive*/, float /*distance*/,
                           float /*cos_light*/, bool /*bidirectional*/, LightHit* /*out*/) const {
    return false;
  }
  // Lights at infinity: radiance arriving along a ray that left the scene in `direction`, and
  // sample_li()'s solid-angle density of it (0 when that sample never draws it).
  virtual Vec3 radiance_at_infinity(const Vec3& /*direction*/,
                                    bool /*bidirectional*/ = false) const {
    return Vec3(0.0f);
  }
  virtual float pdf_at_infinity(const Vec3& /*direction*/, bool /*bidirectional*/ = false) const {
    return 0.0f;
  }
  // sample_li()'s (without bidirectional) density of `direction` at the receiving point `p`:
  // the world's portals make it depend on the point (portal_world.h).
  virtual float pdf_li_at_infinity(const Vec3& /*p*/, const Vec3& direction) const {
    return pdf_at_infinity(direction);
  }

  // --- Emission (photons, light subpaths; Jensen 2001 sec. 5.1) ---
  // A ray leaving the emitter. `u_rest` is what is left of the number that picked this emitter
  // (the group picks a triangle with it, a triangle its side). Without `bidirectional`, its
  // power; with it, its radiance and densities. False when it emits nothing there.
  virtual bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
                         bool bidirectional, EmittedPhoton* out) const = 0;
  // Caustic photons aimed at `targets`, and the share of the flux heading to them.
  virtual bool sample_le_towards(const std::vector<BoundingSphere>& /*targets*/,
                                 const PhotonFrame& /*frame*/, float /*u_pick*/, Vec2 /*u_pos*/,
                                 Vec2 /*u_dir*/, Sampler& /*sampler*/,
                                 EmittedPhoton* /*out*/) const {
    return false;
  }
  virtual float coverage(const std::vector<BoundingSphere>& /*targets*/,
                         float /*scene_radius*/) const {
    return 0.0f;
  }
};

inline float mean_power(const Vec3& p) {
  return (p.x + p.y + p.z) * (1.0f / 3.0f);
}

inline void set_emitted_ray(const Vec3& origin, const Vec3& direction, Ray* ray) {
  ray->origin = origin;
  ray->direction = direction;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
}

// The area density of a uniform point on the disc of radius R that covers the scene.
inline float scene_disc_pdf(const PhotonFrame& frame) {
  return 1.0f / (kPi * frame.radius * frame.radius);
}

}  // namespace photon

// Densities of an emitter's sampling techniques, for bidirectional estimators.
#pragma once

#include <cmath>
#include <cstdint>

#include "photon/base/math.h"

namespace photon {

// Bidirectional estimators (vertex connection and merging, Georgiev et al. 2012; the MIS
// quantities of Davidovic et al. 2012, "Implementing vertex connection and merging") weigh a
// path by the densities of every technique that could have made it, so besides sampling they
// need, per emitter: the density of an emitted ray (position in area measure, direction in
// solid angle), the density of a light sample towards a point, and both densities for a point
// a camera ray met. Lights at infinity measure "position" on the disc across the direction
// that covers the scene (PhotonFrame) and light samples in solid angle; delta positions and
// directions count as discrete probability 1.
enum VcmEmitterFlags : uint8_t {
  kVcmSupported = 1u << 0,       // implements the *_vcm methods below
  kVcmDeltaPosition = 1u << 1,   // a point: camera rays never meet it
  kVcmDeltaDirection = 1u << 2,  // a parallel beam (sun of angle 0)
  kVcmInfinite = 1u << 3,        // at infinity: sun, world
};

// A ray leaving the emitter (the first vertex of a light subpath).
struct EmissionSample {
  Ray ray;
  Vec3 radiance{0.0f};      // Le along ray: W/m^2/sr; a point W/sr; a delta direction W/m^2
  float pdf_pos = 0.0f;     // area density of the origin (1: delta position)
  float pdf_dir = 0.0f;     // solid-angle density of the direction (1: delta direction)
  float cos_light = 1.0f;   // |cos| of the direction to the emitting surface (1: none)
  float direct_pdf = 0.0f;  // density of illuminate_vcm() picking this origin: area measure
                            // (finite), solid angle (infinite), 1 for delta emitters
};

// A light sample towards a receiving point.
struct Illumination {
  Vec3 wi{0.0f};              // from the receiver towards the light
  float distance = 0.0f;      // INFINITY for lights at infinity
  Vec3 radiance{0.0f};        // as EmissionSample::radiance, towards the receiver
  float direct_pdf = 0.0f;    // solid-angle density of wi (delta position: distance^2, so
                              // radiance / direct_pdf is the irradiance; delta direction: 1)
  float emission_pdf = 0.0f;  // pdf_pos * pdf_dir of emit_vcm() making the reverse ray
  float cos_light = 1.0f;
  Vec3 surface_normal{0.0f};  // at the sampled point on scene geometry (emissive triangles)
};

// What a camera ray that met the emitter sees, and how else that point could be sampled.
struct EmitterHit {
  Vec3 radiance{0.0f};
  float distance = INFINITY;
  float direct_pdf = 0.0f;  // illuminate_vcm()'s density: area measure, or solid angle at infinity
  float emission_pdf = 0.0f;  // emit_vcm()'s pdf_pos * pdf_dir for the reverse ray
  float cos_light = 1.0f;     // |cos| of the ray to the emitting surface (1: at infinity)
};

}  // namespace photon

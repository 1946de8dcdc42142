// Everything the radiosity integrator reads from materials, in one place, so a new material
// system only has to re-point these functions. (Rays that meet mirrors and glass are continued
// by trace_specular_chain, specular_chain.cpp, shared with the other integrators.)
#pragma once

#include "photon/scene.h"

namespace photon {

// Whether a surface takes part in the radiosity solution (gets elements, receives and
// reflects power): the Lambertian surfaces. Mirrors and glass only redirect rays.
inline bool is_radiosity_surface(const Material& m) {
  return m.type == MaterialType::kDiffuse;
}

// Per-channel Lambertian reflectance rho in [0, 1] (seed 002 eq. 7's rho_i, one per channel).
inline Vec3 diffuse_reflectance_of(const Material& m) {
  if (!is_radiosity_surface(m) || !is_finite(m.color)) return Vec3(0.0f);
  return min(max(m.color, Vec3(0.0f)), Vec3(1.0f));
}

// Emitted radiance L_e (W / m^2 / sr, each side), as the other integrators read it.
inline Vec3 emitted_radiance_of(const Material& m) {
  return is_finite(m.emission) ? max(m.emission, Vec3(0.0f)) : Vec3(0.0f);
}

}  // namespace photon

// Reflection, refraction and the dielectric Fresnel equations.
#pragma once

#include "photon/base/math.h"

namespace photon {

// Mirror direction of `wi` (pointing away from the surface) about `n`.
inline Vec3 reflect(const Vec3& wi, const Vec3& n) {
  return n * (2.0f * dot(wi, n)) - wi;
}

// Unpolarised Fresnel reflectance of a dielectric interface. `cos_i` is the cosine between the
// incident direction and the normal on the incident side (>= 0); `eta` = n_transmitted /
// n_incident. Returns 1 on total internal reflection.
float fresnel_dielectric(float cos_i, float eta);

// Snell's law: refracts `wi` (pointing away from the surface, on the side `n` points to) with
// relative index `eta` = n_transmitted / n_incident. Returns false on total internal reflection.
bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt);

}  // namespace photon

// Warping functions from the unit square to geometric domains, with their densities.
#pragma once

#include "photon/base/math.h"

namespace photon {

// Shirley and Chiu 1997, "A Low Distortion Map Between Disk and Square". Unit disk, pdf 1/pi.
Vec2 sample_concentric_disk(Vec2 u);

// The inverse of sample_concentric_disk: the unit-square point that maps to disk point `d`.
Vec2 invert_concentric_disk(Vec2 d);
// Malley's method: project a disk sample onto the hemisphere around +z. pdf = cos(theta) / pi.
Vec3 sample_cosine_hemisphere(Vec2 u);
inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0 ? cos_theta * kInvPi : 0;
}

// Uniform direction on the unit sphere, pdf 1 / (4 pi).
Vec3 sample_uniform_sphere(Vec2 u);

// Uniform direction inside the cone of half-angle acos(cos_max) around +z,
// pdf 1 / (2 pi (1 - cos_max)).
Vec3 sample_uniform_cone(Vec2 u, float cos_max);
inline float uniform_cone_pdf(float cos_max) {
  return 1.0f / (2.0f * kPi * (1.0f - cos_max));
}

// Barycentric coordinates (b0, b1) of a uniform point on a triangle (Heitz 2019, low distortion).
Vec2 sample_uniform_triangle(Vec2 u);

}  // namespace photon

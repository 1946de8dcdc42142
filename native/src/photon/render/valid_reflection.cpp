#include "photon/render/valid_reflection.h"

#include <algorithm>
#include <cmath>

namespace photon {

Vec3 ensure_valid_reflection(const Vec3& ng, const Vec3& i, const Vec3& n) {
  const float t = std::min(0.9f * dot(ng, i), 0.01f);
  const Vec3 r = n * (2.0f * dot(n, i)) - i;
  if (dot(ng, r) >= t) return n;

  // A frame with Ng as z and N in the x-z plane; N' = (sqrt(1 - z^2), z) in it. Writing
  // R'.z = 2 (N'.I) N'.z - I.z = t with N'.I = sqrt(1 - z^2) I.x + z I.z and squaring gives
  // a quadratic in z^2 with roots z^2 = (c +- b) / (2a), a = Ix^2 + Iz^2,
  // b = sqrt(Ix^2 (a - t^2)), c = Iz t + a. Squaring admits spurious roots, so candidates are
  // told apart by the reflection they produce.
  const Vec3 tangent = n - ng * dot(n, ng);
  const float tangent_len2 = length_squared(tangent);
  if (!(tangent_len2 > 0.0f)) return ng;
  const Vec3 x = tangent / std::sqrt(tangent_len2);
  const float ix = dot(i, x), iz = dot(i, ng);
  const float a = ix * ix + iz * iz;
  if (!(a > 0.0f)) return ng;
  const float b = std::sqrt(std::max(ix * ix * (a - t * t), 0.0f));
  const float c = iz * t + a;

  struct Candidate {
    float nx, nz, rz;  // N' in the (x, Ng) frame and its reflection's height R'.z
  };
  Candidate found[2];
  int count = 0;
  for (const float z2 : {0.5f * (c + b) / a, 0.5f * (c - b) / a}) {
    if (!(z2 > 1e-5f && z2 <= 1.0f + 1e-5f)) continue;
    const float nz = std::sqrt(std::min(z2, 1.0f));
    const float nx = std::sqrt(std::max(1.0f - z2, 0.0f));
    found[count++] = {nx, nz, 2.0f * (nx * ix + nz * iz) * nz - iz};
  }
  if (count == 0) return ng;
  Candidate pick = found[0];
  if (count == 2) {
    // Of two reflections above the surface the shallower one (the smaller turn from N);
    // otherwise the one that is higher.
    const bool both_above = found[0].rz >= 1e-5f && found[1].rz >= 1e-5f;
    const bool second = both_above ? found[1].rz < found[0].rz : found[1].rz > found[0].rz;
    if (second) pick = found[1];
  }
  return x * pick.nx + ng * pick.nz;
}

}  // namespace photon

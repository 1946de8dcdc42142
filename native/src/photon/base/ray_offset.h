// Spawning rays off surfaces without re-hitting them, at any scene scale.
//
// A computed hit point p carries a rounding error that grows with the magnitudes of the numbers
// it came from: the ray origin, p itself and the triangle's vertices. An offset along the
// geometric normal must exceed that error (Wächter and Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems ch. 6; pbrt-v4's OffsetRayOrigin), so it has a
// term relative to |p| and a term for points near the origin, where |p| says nothing of the error
// of a far ray origin or vertex. That second term must be a length of the scene, not an absolute
// constant: an absolute 1e-4 m floor pushes rays of a 0.1 mm scene clean through it.
#pragma once

#include <algorithm>
#include <cmath>

#include "photon/base/math.h"

namespace photon {

// Relative size of the offset: 1e-4 of (scene length + |p|), about 840 float ulps of |p|, a
// wide margin over Embree's hit error (Wächter and Binder use 256 ulps).
constexpr float kRayOffsetRelative = 1e-4f;

// The scene length that absolute distances of the renderer are expressed in: 1 m for scenes of
// a metre or more (where the former absolute constants were tuned, so such scenes render as
// before), the scene's bounding-box diagonal below that, so a scene scaled down renders the same
// image. An empty or non-finite box gives 1.
inline float scene_length_scale(const Vec3& bounds_min, const Vec3& bounds_max) {
  const float diagonal = length(bounds_max - bounds_min);
  if (!(diagonal > 0.0f) || !std::isfinite(diagonal)) return 1.0f;
  return std::min(1.0f, diagonal);
}

// Offsets a ray origin off the surface along the geometric normal ng (unit length), on the side
// `w` leaves to, so a spawned ray does not re-hit its own triangle. `length_scale` is
// scene_length_scale() of the scene.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& ng, const Vec3& w, float length_scale) {
  const float eps = kRayOffsetRelative * (length_scale + max_abs_component(p));
  return dot(ng, w) >= 0.0f ? p + ng * eps : p - ng * eps;
}

// True when 32-bit floats cannot place the scene's geometry finely enough: its distance from the
// origin (largest |coordinate|) is over 128 times its extent, so one float step there is over
// 2^-16 of the extent and the ray offset above over 1% of it (surfaces band, contact shadows
// and light leaks show).
constexpr float kFarFromOriginRatio = 128.0f;
inline bool scene_beyond_float_precision(const Vec3& bounds_min, const Vec3& bounds_max,
                                         float ratio = kFarFromOriginRatio) {
  const float extent = length(bounds_max - bounds_min);
  const float distance = std::max(max_abs_component(bounds_min), max_abs_component(bounds_max));
  if (!std::isfinite(extent) || !std::isfinite(distance)) return false;
  return distance > ratio * extent;
}

// The same test for one object (an instance's world box) of a scene that is itself near the
// origin but far larger than its objects (a 1e7 m scene with metre-sized objects at its edge):
// beyond this ratio the ray offset above exceeds 80% of the object's size and one float step is
// 2^-10 of it, so the object's own shading is lost. Higher than the scene's ratio because
// scattered small objects (grass, pebbles) a few hundred sizes out still render acceptably.
constexpr float kObjectFarFromOriginRatio = 8192.0f;

}  // namespace photon

// Triangles of emissive materials as light sources: sampled for direct light (by power, then
// uniformly by area), looked up for multiple importance sampling when a BSDF-sampled ray hits
// one, and used as photon emitters. Emission is two-sided, as in Cycles.
#pragma once

#include <unordered_map>
#include <vector>

#include "photon/base/distribution.h"
#include "photon/lights/lights.h"
#include "photon/render/accel.h"
#include "photon/shading/textures.h"

namespace photon {

struct EmissiveTriangle {
  Vec3 p0, e1, e2;  // world space: p = p0 + b1 e1 + b2 e2
  Vec3 normal;      // unit
  float area = 0.0f;
  Vec3 radiance;  // emitted radiance, each side
};

class EmissiveMeshes {
 public:
  EmissiveMeshes() = default;
  EmissiveMeshes(const Scene& scene, const Accel& accel, const TextureSet* textures = nullptr);

  bool empty() const { return triangles_.empty(); }
  size_t size() const { return triangles_.size(); }
  const EmissiveTriangle& triangle(size_t i) const { return triangles_[i]; }
  // Total emitted flux, W per channel (both sides: 2 pi L A per triangle).
  Vec3 power() const { return power_; }

  // Picks a triangle by power and a uniform point on it, as seen from `p`. `out->pdf` is the
  // solid-angle density of the chosen direction.
  bool sample(const Vec3& p, float u_pick, Vec2 u_point, LightSample* out) const;
  // Solid-angle density with which sample() picks the direction to a point of the triangle
  // hit by a ray (Embree instance / primitive), at distance `distance` with cosine
  // `cos_light` between the ray and the triangle's normal. 0 if that triangle is not emissive.
  float pdf(uint32_t instance, uint32_t primitive, float distance, float cos_light) const;

  // Photon emission: a point by power and area, a side, and a cosine-distributed direction.
  // `power` is the photon's flux for one photon (divide by the photon count).
  void emit(float u_pick, Vec2 u_point, Vec2 u_dir, Ray* ray, Vec3* power) const;
  // A point chosen by power (and the side chosen by `u_side`), for emission towards a target.
  size_t pick_point(float u_pick, Vec2 u_point, Vec3* point, Vec3* normal) const;
  float pick_probability(size_t i) const { return distribution_.probability(i); }
  // A triangle by power; `remapped` gets u rescaled inside its interval (Distribution1D).
  size_t pick(float u, float* remapped) const { return distribution_.sample(u, remapped); }
  // The triangle an Embree hit (instance, primitive) is on, or -1 if it does not emit.
  long find(uint32_t instance, uint32_t primitive) const {
    auto it = index_.find((static_cast<uint64_t>(instance) << 32) | primitive);
    return it == index_.end() ? -1 : static_cast<long>(it->second);
  }
  float length_scale() const { return length_scale_; }

 private:
  std::vector<EmissiveTriangle> triangles_;
  Distribution1D distribution_;
  std::unordered_map<uint64_t, uint32_t> index_;  // (instance << 32 | primitive) -> triangle
  float length_scale_ = 1.0f;                     // Accel::length_scale(), for ray offsets
  Vec3 power_{0.0f};
};

}  // namespace photon

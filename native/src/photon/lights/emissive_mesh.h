// The triangles of emissive materials in world space, with their radiance and the distribution
// that picks them by power: the data the emissive lights (emissive_lights.h) sample, and the
// lookup of a triangle a ray hit.
#pragma once

#include <unordered_map>
#include <vector>

#include "photon/base/distribution.h"
#include "photon/render/accel.h"
#include "photon/scene/scene.h"
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

  float pick_probability(size_t i) const { return distribution_.probability(i); }
  // A triangle by power; `remapped` gets u rescaled inside its interval (Distribution1D).
  size_t pick(float u, float* remapped) const { return distribution_.sample(u, remapped); }
  size_t pick(float u) const { return distribution_.sample(u); }
  bool distribution_empty() const { return distribution_.empty(); }
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

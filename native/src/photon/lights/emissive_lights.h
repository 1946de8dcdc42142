// Emissive triangles as lights, two-sided as in Cycles: one by one for the light tree
// (TriangleEmitter), or all of them as one emitter that picks a triangle by power
// (EmissiveGroupEmitter: the every-light estimator and photon emission).
//  - Direct lighting: a triangle by power (the group), a uniform point on it; density
//    P / A * d^2 / |cos| in solid angle.
//  - Photons: a triangle by power, a uniform point, a side (1/2), a cosine-distributed
//    direction: flux 2 pi L A / P. Caustic photons head from a point into a target's cone.
//  - Bidirectional estimators: the same emitted ray, pdf_pos = P / A and pdf_dir =
//    cos / (2 pi); light samples pick the same point, P / A in area measure.
#pragma once

#include "photon/lights/emissive_mesh.h"
#include "photon/lights/emitter.h"

namespace photon {

// All emissive triangles as one emitter: a triangle by power, then a uniform point on it.
class EmissiveGroupEmitter final : public Emitter {
 public:
  explicit EmissiveGroupEmitter(const EmissiveMeshes& meshes) : meshes_(meshes) {}
  EmitterKind kind() const override { return EmitterKind::kSurface; }
  uint8_t flags() const override { return kEmitterBidirectional; }
  LightBounds bounds() const override;
  Vec3 power(float) const override { return meshes_.power(); }
  // A pick of the triangle and a 2D point on it.
  LightSampleU draw_li(Sampler& sampler) const override;
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return true; }
  bool surface_hit(uint32_t instance, uint32_t primitive, float distance, float cos_light,
                   bool bidirectional, LightHit* out) const override;
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;
  bool sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                         float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                         EmittedPhoton* out) const override;
  // The group aims at targets from its triangles' points; a coarse share is enough, the
  // photons' power corrects for it.
  float coverage(const std::vector<BoundingSphere>& targets, float) const override {
    return targets.empty() ? 0.0f : 0.5f;
  }

 private:
  const EmissiveMeshes& meshes_;
};

// One emissive triangle: a uniform point on it.
class TriangleEmitter final : public Emitter {
 public:
  TriangleEmitter(const EmissiveMeshes& meshes, size_t index) : meshes_(meshes), index_(index) {}
  EmitterKind kind() const override { return EmitterKind::kSurface; }
  uint8_t flags() const override { return kEmitterBidirectional; }
  LightBounds bounds() const override;
  Vec3 power(float) const override;
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return true; }
  bool surface_hit(uint32_t instance, uint32_t primitive, float distance, float cos_light,
                   bool bidirectional, LightHit* out) const override;
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;

 private:
  const EmissiveMeshes& meshes_;
  size_t index_;
};

}  // namespace photon

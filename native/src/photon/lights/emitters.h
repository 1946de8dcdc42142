// The emitters Photon has: each Blender lamp, emissive triangles (one by one for the light tree,
// all together as one power-sampled group for the every-light estimator and photon emission),
// and the constant world colour.
#pragma once

#include "photon/lights/emissive_mesh.h"
#include "photon/lights/emitter.h"
#include "photon/lights/lights.h"

namespace photon {

inline float mean_power(const Vec3& p) {
  return (p.x + p.y + p.z) * (1.0f / 3.0f);
}

class LampEmitter final : public Emitter {
 public:
  LampEmitter(const LightSet& lamps, size_t index) : lamps_(lamps), index_(index) {}
  EmitterKind kind() const override { return EmitterKind::kLamp; }
  bool sample(const Vec3& p, Sampler& sampler, LightSample* out) const override {
    return lamps_.sample(index_, p, sampler.get_2d(), out);
  }
  bool has_area() const override { return lamps_.has_area(index_); }
  bool eval(const Vec3& p, const Vec3& wi, Vec3* radiance, float* distance,
            float* pdf) const override {
    return lamps_.eval(index_, p, wi, radiance, distance, pdf);
  }
  SampledSpectrum spectrum(const Vec3& rgb, const SampledWavelengths& wl) const override {
    return lamps_.spectrum(index_, rgb, wl);
  }
  Vec3 power(float scene_radius) const override { return lamps_.power(index_, scene_radius); }
  void emit(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
            EmittedPhoton* out) const override {
    lamps_.emit(index_, frame.center, frame.radius, u_pos, u_dir, out);
  }
  bool emit_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                    float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler&,
                    EmittedPhoton* out) const override {
    return lamps_.emit_towards(index_, targets, frame.center, frame.radius, u_pick, u_pos, u_dir,
                               out);
  }
  float coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const override {
    return lamps_.coverage(index_, targets, scene_radius);
  }
  LightBounds bounds() const override;

  uint8_t vcm_flags() const override { return lamps_.vcm_flags(index_); }
  bool emit_vcm(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
                EmissionSample* out) const override {
    return lamps_.emit_vcm(index_, frame.center, frame.radius, u_pos, u_dir, out);
  }
  bool illuminate_vcm(const PhotonFrame& frame, const Vec3& p, float, Vec2 u,
                      Illumination* out) const override {
    return lamps_.illuminate_vcm(index_, frame.radius, p, u, out);
  }
  bool hit_vcm(const PhotonFrame& frame, const Ray& ray, float tmax,
               EmitterHit* out) const override {
    return lamps_.hit_vcm(index_, frame.radius, ray, tmax, out);
  }

 private:
  const LightSet& lamps_;
  size_t index_;
};

// All emissive triangles as one emitter: a triangle by power, then a uniform point on it.
class EmissiveGroupEmitter final : public Emitter {
 public:
  explicit EmissiveGroupEmitter(const EmissiveMeshes& meshes) : meshes_(meshes) {}
  EmitterKind kind() const override { return EmitterKind::kSurface; }
  bool sample(const Vec3& p, Sampler& sampler, LightSample* out) const override {
    const float u_pick = sampler.get_1d();
    const Vec2 u_point = sampler.get_2d();
    return meshes_.sample(p, u_pick, u_point, out);
  }
  bool has_area() const override { return true; }
  float surface_pdf(uint32_t instance, uint32_t primitive, float distance,
                    float cos_light) const override {
    return meshes_.pdf(instance, primitive, distance, cos_light);
  }
  Vec3 power(float) const override { return meshes_.power(); }
  void emit(const PhotonFrame&, float u_rest, Vec2 u_pos, Vec2 u_dir,
            EmittedPhoton* out) const override {
    meshes_.emit(u_rest, u_pos, u_dir, &out->ray, &out->power);
  }
  bool emit_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                    float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                    EmittedPhoton* out) const override;
  // The group aims at targets from its triangles' points; a coarse share is enough, the
  // photons' power corrects for it.
  float coverage(const std::vector<BoundingSphere>& targets, float) const override {
    return targets.empty() ? 0.0f : 0.5f;
  }
  LightBounds bounds() const override;

  // Two-sided: a point by power and area, a side with probability 1/2, a cosine direction.
  uint8_t vcm_flags() const override { return kVcmSupported; }
  bool emit_vcm(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
                EmissionSample* out) const override;
  bool illuminate_vcm(const PhotonFrame& frame, const Vec3& p, float u_rest, Vec2 u,
                      Illumination* out) const override;
  bool surface_hit_vcm(uint32_t instance, uint32_t primitive, float cos_light,
                       EmitterHit* out) const override;

 private:
  const EmissiveMeshes& meshes_;
};

// One emissive triangle: a uniform point on it; two-sided, as in Cycles.
class TriangleEmitter final : public Emitter {
 public:
  TriangleEmitter(const EmissiveMeshes& meshes, size_t index) : meshes_(meshes), index_(index) {}
  EmitterKind kind() const override { return EmitterKind::kSurface; }
  bool sample(const Vec3& p, Sampler& sampler, LightSample* out) const override;
  bool has_area() const override { return true; }
  float surface_pdf(uint32_t instance, uint32_t primitive, float distance,
                    float cos_light) const override;
  Vec3 power(float) const override;
  void emit(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
            EmittedPhoton* out) const override;
  LightBounds bounds() const override;

  // Two-sided: a point by power and area, a side with probability 1/2, a cosine direction.
  uint8_t vcm_flags() const override { return kVcmSupported; }
  bool emit_vcm(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
                EmissionSample* out) const override;
  bool illuminate_vcm(const PhotonFrame& frame, const Vec3& p, float u_rest, Vec2 u,
                      Illumination* out) const override;
  bool surface_hit_vcm(uint32_t instance, uint32_t primitive, float cos_light,
                       EmitterHit* out) const override;

 private:
  const EmissiveMeshes& meshes_;
  size_t index_;
};

// A constant world colour: light from every direction, reached by BSDF-sampled rays that leave
// the scene; photons enter through a disc covering the scene.
class WorldEmitter final : public Emitter {
 public:
  explicit WorldEmitter(const Vec3& color) : color_(max(color, Vec3(0.0f))) {}
  EmitterKind kind() const override { return EmitterKind::kWorld; }
  bool sample(const Vec3&, Sampler&, LightSample*) const override { return false; }
  bool has_area() const override { return true; }
  Vec3 radiance_at_infinity(const Vec3&) const override { return color_; }
  // 4 pi sr of radiance L through the disc pi R^2.
  Vec3 power(float scene_radius) const override {
    return color_ * (4.0f * kPi * kPi * scene_radius * scene_radius);
  }
  void emit(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
            EmittedPhoton* out) const override;
  LightBounds bounds() const override;

  // Uniform directions (1 / (4 pi)) for light samples and emitted rays.
  uint8_t vcm_flags() const override { return kVcmSupported | kVcmInfinite; }
  bool emit_vcm(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir,
                EmissionSample* out) const override;
  bool illuminate_vcm(const PhotonFrame& frame, const Vec3& p, float u_rest, Vec2 u,
                      Illumination* out) const override;
  bool hit_vcm(const PhotonFrame& frame, const Ray& ray, float tmax,
               EmitterHit* out) const override;

 private:
  Vec3 color_;
};

}  // namespace photon

// A constant world colour: light from every direction, reached in direct lighting by
// BSDF-sampled rays that leave the scene (a light sample of it would only add noise). Photons
// enter along a uniform direction through a disc covering the scene: flux 4 pi^2 R^2 L.
// Bidirectional estimators sample it uniformly (1 / (4 pi)) for light samples and emitted rays.
#pragma once

#include "photon/lights/emitter.h"

namespace photon {

class WorldEmitter final : public Emitter {
 public:
  explicit WorldEmitter(const Vec3& color) : color_(max(color, Vec3(0.0f))) {}
  EmitterKind kind() const override { return EmitterKind::kWorld; }
  uint8_t flags() const override {
    return kEmitterBidirectional | kEmitterInfinite | kEmitterBsdfSampledOnly;
  }
  LightBounds bounds() const override;
  // 4 pi sr of radiance L through the disc pi R^2.
  Vec3 power(float scene_radius) const override {
    return color_ * (4.0f * kPi * kPi * scene_radius * scene_radius);
  }
  // Direct lighting draws nothing for it: it is not light-sampled there.
  LightSampleU draw_li(Sampler&) const override { return LightSampleU{}; }
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return true; }
  Vec3 radiance_at_infinity(const Vec3&, bool = false) const override { return color_; }
  float pdf_at_infinity(const Vec3&, bool bidirectional = false) const override {
    return bidirectional ? kInv4Pi : 0.0f;
  }
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;

 private:
  Vec3 color_;
};

// A ray along `d` through a uniform point (for `u_pos`) of the disc across d that covers the
// scene: how light from infinity enters it.
void ray_from_infinity(const PhotonFrame& frame, const Vec3& d, Vec2 u_pos, Ray* ray);

}  // namespace photon

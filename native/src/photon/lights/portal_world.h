// The world seen through portals: wraps the world's emitter (environment.h, or the uniform
// world of world_light.h) and adds the portals as sampling techniques, as Cycles 3.4 does
// (kernel/light/background.h): a light sample at a point that portals face goes through a
// portal or follows the world's own directions, one or the other with even odds (Cycles'
// weights 1 and 1 without a sun), and its density is the mixture's, also for BSDF samples that
// leave the scene (one-sample MIS, Veach 1997 sec. 9.2.4). Elsewhere the world samples as
// before. The uniform world, otherwise reached by BSDF samples only, gets light samples too:
// through the portals and uniform over the sphere.
//
// Photons: half of them enter along lines through the portals (portals.h), half as the world
// sends them without portals; each carries the radiance over the mixture's density of its line
// (in projected area x solid angle), so light that reaches the room by other ways is still
// counted once. Light subpaths (VCM) and caustic photons aimed at objects use the world alone.
#pragma once

#include "photon/lights/emitter.h"
#include "photon/lights/portals.h"

namespace photon {

class PortalWorldEmitter final : public Emitter {
 public:
  static constexpr float kPortalShare = 0.5f;

  // `world` must outlive it; `portals` must not be empty.
  PortalWorldEmitter(const Emitter& world, PortalSet portals);

  EmitterKind kind() const override { return EmitterKind::kWorld; }
  uint8_t flags() const override { return world_.flags() & ~kEmitterBsdfSampledOnly; }
  LightBounds bounds() const override { return world_.bounds(); }
  Vec3 power(float scene_radius) const override { return world_.power(scene_radius); }
  SampledSpectrum spectrum(const Vec3& rgb, const SampledWavelengths& wl) const override {
    return world_.spectrum(rgb, wl);
  }

  // A pick (portal or world, and which portal) and a 2D sample.
  LightSampleU draw_li(Sampler& sampler) const override;
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return true; }
  Vec3 radiance_at_infinity(const Vec3& direction, bool bidirectional = false) const override {
    return world_.radiance_at_infinity(direction, bidirectional);
  }
  // Without a point: the world's own density (what bidirectional estimators use).
  float pdf_at_infinity(const Vec3& direction, bool bidirectional = false) const override {
    return world_.pdf_at_infinity(direction, bidirectional);
  }
  float pdf_li_at_infinity(const Vec3& p, const Vec3& direction) const override;

  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;
  bool sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                         float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                         EmittedPhoton* out) const override {
    return world_.sample_le_towards(targets, frame, u_pick, u_pos, u_dir, sampler, out);
  }
  float coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const override {
    return world_.coverage(targets, scene_radius);
  }

  const PortalSet& portals() const { return portals_; }

 private:
  // The world's own solid-angle density of light samples: its table (an environment) or uniform
  // (the uniform world), as its bidirectional light samples draw them.
  float world_pdf(const Vec3& direction) const { return world_.pdf_at_infinity(direction, true); }
  // The mixture's density of a line along `direction` (the way the light travels) through
  // `point`, crossing `crossings` portals, in projected area x solid angle.
  float line_pdf(const PhotonFrame& frame, const Vec3& point, const Vec3& direction,
                 int crossings) const;

  const Emitter& world_;
  PortalSet portals_;
};

}  // namespace photon

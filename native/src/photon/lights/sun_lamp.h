// Sun lamps of strength S: irradiance S W/m^2 on a surface facing them, from a disc of
// directions of the sun's angular diameter (a parallel beam at angle 0).
//  - Direct lighting: a direction uniform in the disc of directions, weight S.
//  - Rays that leave the scene towards the disc see radiance S / (pi tan^2(angle / 2)).
//  - Photons: a parallel beam along the sun's axis (directions spread over the disc) through a
//    disc that covers the scene, flux S pi R^2; caustic photons through the targets'
//    footprints across the beam (photon_aim.h).
//  - Bidirectional estimators: a point uniform on the scene's disc (1 / (pi R^2)) and a
//    direction uniform in the sun's cone, radiance S / (solid angle of the cone), so the disc
//    gives irradiance S; a sun of angle 0 is a parallel beam of irradiance S.
#pragma once

#include "photon/lights/lamp.h"

namespace photon {

class SunLamp final : public Lamp {
 public:
  explicit SunLamp(LampDescription d);

  uint8_t flags() const override;
  Vec3 power(float scene_radius) const override;
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return false; }
  Vec3 radiance_at_infinity(const Vec3& direction, bool bidirectional) const override;
  float pdf_at_infinity(const Vec3& direction, bool bidirectional) const override;
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;
  bool sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                         float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                         EmittedPhoton* out) const override;
  float coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const override;

 private:
  LightBounds extent() const override;
  bool delta() const { return sun_cos_max_ >= 1.0f; }

  Vec3 axis_;          // the direction the light travels (world -Z of the lamp), unit
  Vec3 irradiance_;    // W/m^2
  Vec3 radiance_;      // of the sun's disc, W/m^2/sr (0 for a parallel beam)
  float sun_cos_max_;  // cos of half the sun's angular diameter
};

std::unique_ptr<Lamp> make_sun_lamp(LampDescription d);

}  // namespace photon

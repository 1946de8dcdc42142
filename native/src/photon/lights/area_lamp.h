// Area lamps of power P and area A (rectangle, square, disc, ellipse): one-sided, uniform
// radiance L = P / (4 A) (Cycles' eval_fac of 0.25 / A), emitted down the lamp's local -Z axis.
//  - Direct lighting: a uniform point of the lamp, density d^2 / (cos A) in solid angle.
//  - Photons: a uniform point and a cosine-distributed direction, flux pi L A; caustic photons
//    only into the part of the lamp's hemisphere that heads into a target (photon_aim.h).
//  - Bidirectional estimators: the same point (1 / A) and direction (cos / pi).
// A spread narrower than 180 degrees (area_spread.h) scales the radiance by a(theta) and keeps
// the power: photons leave with directions distributed as cos a / pi, caustic photons aim only
// within the spread's cone, and direct lighting samples only the part of the lamp that can
// reach the receiver (as Cycles 3.x does for rectangles), so narrow spreads stay smooth.
// An IES profile read per direction (Cycles 4.0+) scales the radiance along each direction it
// leaves in; directions are sampled as without it, weighted by it.
#pragma once

#include "photon/base/spherical_caps.h"
#include "photon/lights/area_spread.h"
#include "photon/lights/lamp.h"

namespace photon {

class AreaLamp final : public Lamp {
 public:
  explicit AreaLamp(LampDescription d);

  uint8_t flags() const override { return kEmitterBidirectional; }
  Vec3 power(float scene_radius) const override;
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return true; }
  bool eval_li(const Vec3& p, const Vec3& wi, LightHit* out) const override;
  bool intersect(const Ray& ray, float tmax, bool bidirectional, LightHit* out) const override;
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;
  bool sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                         float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                         EmittedPhoton* out) const override;
  float coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const override;
  float area() const { return area_; }

 private:
  LightBounds extent() const override;
  // A uniform point of the lamp for `u`.
  Vec3 point(Vec2 u) const;
  // Whether the point d (relative to the centre, in the lamp's plane) lies on the lamp.
  bool inside(const Vec3& d) const;
  // The part of the lamp direct lighting samples for a receiver at p: the whole lamp, or
  // with a spread, the part of its bounding rectangle within tan(h) * distance of p's foot
  // point in each axis (outside it a(theta) is 0), in the lamp's coordinates scaled to
  // [-1, 1], with its area in the lamp's plane. False if no point of the lamp reaches p.
  struct Window {
    bool whole = true;
    float u0 = -1.0f, u1 = 1.0f, v0 = -1.0f, v1 = 1.0f;
    float area = 0.0f;
  };
  bool direct_window(const Vec3& p, Window* w) const;
  // sample_li's end with a spread: `window_area` is the part of the lamp it sampled.
  bool sample_spread_li(float cos_light, float dist2, float window_area, bool bidirectional,
                        LightSample* out) const;
  // The directions it emits into: its hemisphere, or its spread's cone.
  Cap emission_cap() const;
  // The IES profile's factor along a direction leaving the lamp (1 without one).
  float profile(const Vec3& dir) const { return ies_ ? ies_->factor(dir) : 1.0f; }

  AreaShape shape_;
  Vec3 position_;
  Vec3 axis_;             // emission direction (world -Z of the lamp), unit
  Vec3 half_u_, half_v_;  // half extents in world space
  Vec3 radiance_;         // W/m^2/sr
  float area_;
  float radius_;  // Blender's lamp radius, widening the cone of caustic aiming
  AreaSpread spread_;
  std::optional<IesEmission> ies_;
  Vec3 flux_;
};

// The area lamp of `d`, or null (with a warning) when its size is zero.
std::unique_ptr<Lamp> make_area_lamp(LampDescription d, std::vector<std::string>* warnings);

}  // namespace photon

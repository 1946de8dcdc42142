// Point and spot lamps of power P: radiant intensity I = P / (4 pi) W/sr (a spot: times Cycles'
// cone attenuation).
//  - Direct lighting: a lamp with a radius r is a disc of radius r facing the shaded point
//    (Cycles 3.x's "sphere" light), of radiance I / (pi r^2).
//  - Photons: a point emits uniform directions, flux 4 pi I; with a radius, a uniform point on
//    the sphere and a cosine-distributed direction around its normal; a spot uniform directions
//    in its cone, weighted by the attenuation.
//  - Caustic photons go where the lamp's emission and a target's cone overlap (photon_aim.h):
//    the spot's cone, or the side of a sphere lamp facing the target.
//  - Bidirectional estimators: a lamp with a radius is a Lambertian sphere of radiance
//    L = I / (pi r^2) (times the spot's attenuation along the direction of travel), which has
//    the intensity I of the point in every direction and which camera rays meet. An emitted ray
//    takes its direction first (uniform, or uniform in the cone) and then a uniform point on
//    the hemisphere facing it (1 / (2 pi r^2)); a light sample takes a uniform point on the
//    whole sphere (1 / (4 pi r^2)), of which the half facing the receiver lights it. Without a
//    radius: a uniform direction, intensity I.
#pragma once

#include "photon/lights/lamp.h"

namespace photon {

class PointLamp final : public Lamp {
 public:
  explicit PointLamp(LampDescription d);

  uint8_t flags() const override;
  Vec3 power(float scene_radius) const override;
  bool sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                 LightSample* out) const override;
  bool has_area() const override { return radius_ > 0.0f; }
  bool eval_li(const Vec3& p, const Vec3& wi, LightHit* out) const override;
  bool intersect(const Ray& ray, float tmax, bool bidirectional, LightHit* out) const override;
  bool sample_le(const PhotonFrame& frame, float u_rest, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                 EmittedPhoton* out) const override;
  bool sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame& frame,
                         float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler& sampler,
                         EmittedPhoton* out) const override;
  float coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const override;

 private:
  LightBounds extent() const override;
  // Cycles 3.x spot_attenuation: the cosine to the axis, faded to zero over the blend region
  // (1 for a point lamp), times the IES profile's factor.
  float attenuation(const Vec3& dir_from_light) const;
  float spot_attenuation(const Vec3& dir_from_light) const;
  // The direction of an emitted ray: uniform, uniform in the spot's cone, or the profile's
  // (of density direction_pdf).
  Vec3 sample_direction(Vec2 u) const;
  // A lamp with a radius, which bidirectional estimators treat as a sphere; the direction
  // density of its emitted rays, and its radiance along a direction of travel d.
  bool sphere() const { return radius_ > 0.0f && area_ > 0.0f; }
  float direction_pdf(const Vec3& d) const;
  Vec3 sphere_radiance(const Vec3& d) const {
    return spot_ || ies_ ? radiance_ * attenuation(d) : radiance_;
  }
  bool sample_sphere_li(const Vec3& p, Vec2 u, LightSample* out) const;
  bool emit_from_sphere(Vec2 u_pos, Vec2 u_dir, EmittedPhoton* out) const;

  bool spot_;
  Vec3 position_;
  Vec3 axis_;       // the spot's direction (world -Z of the lamp), unit
  Vec3 intensity_;  // W/sr
  Vec3 radiance_;   // of the disc or sphere of the lamp's radius, W/m^2/sr
  float radius_;
  float area_;  // pi r^2
  float cos_half_spot_;
  float spot_smooth_;
  bool spot_cosine_;  // Light::spot_cosine_falloff
  std::optional<IesEmission> ies_;
  Vec3 flux_;
};

std::unique_ptr<Lamp> make_point_lamp(LampDescription d);

}  // namespace photon

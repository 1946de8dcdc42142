#include "photon/lights/sun_lamp.h"

#include "photon/base/sampling.h"
#include "photon/lights/photon_aim.h"

namespace photon {

std::unique_ptr<Lamp> make_sun_lamp(LampDescription d) {
  return std::make_unique<SunLamp>(std::move(d));
}

SunLamp::SunLamp(LampDescription d) : Lamp(d.light->visibility, std::move(d.spectrum)) {
  const Light& l = *d.light;
  axis_ = normalize(-l.light_to_world.column(2));
  irradiance_ = d.flux_color;
  const float half = std::clamp(l.sun_angle, 0.0f, kPi) * 0.5f;
  sun_cos_max_ = std::cos(half);
  const float tan_half = std::tan(std::min(half, 1.5f));
  radiance_ = tan_half > 1e-6f ? d.flux_color / (kPi * tan_half * tan_half) : Vec3(0.0f);
}

uint8_t SunLamp::flags() const {
  return kEmitterBidirectional | kEmitterInfinite | (delta() ? kEmitterDeltaDirection : 0);
}

Vec3 SunLamp::power(float scene_radius) const {
  return irradiance_ * (kPi * scene_radius * scene_radius);
}

LightBounds SunLamp::extent() const {
  LightBounds b;
  b.infinite = true;
  b.lo = b.hi = Vec3(0.0f);
  return b;
}

bool SunLamp::sample_li(const Vec3&, const LightSampleU& u, const PhotonFrame* bidirectional,
                        LightSample* out) const {
  out->surface_normal = Vec3(0.0f);
  const Frame frame(-axis_);
  out->distance = INFINITY;
  if (bidirectional) {
    out->wi = delta() ? -axis_ : frame.to_world(sample_uniform_cone(u.uv, sun_cos_max_));
    const float cone = delta() ? 1.0f : uniform_cone_pdf(sun_cos_max_);
    out->radiance = irradiance_ * cone;
    out->direct_pdf = cone;
    out->emission_pdf = cone * scene_disc_pdf(*bidirectional);
    out->cos_light = 1.0f;
    return true;
  }
  out->wi = sun_cos_max_ < 1.0f ? frame.to_world(sample_uniform_cone(u.uv, sun_cos_max_)) : -axis_;
  out->weight = irradiance_;
  return true;
}

Vec3 SunLamp::radiance_at_infinity(const Vec3& direction, bool bidirectional) const {
  if (delta() || !(dot(-direction, axis_) >= sun_cos_max_)) return Vec3(0.0f);
  return bidirectional ? irradiance_ * uniform_cone_pdf(sun_cos_max_) : radiance_;
}

float SunLamp::pdf_at_infinity(const Vec3& direction, bool bidirectional) const {
  if (!bidirectional || delta() || !(dot(-direction, axis_) >= sun_cos_max_)) return 0.0f;
  return uniform_cone_pdf(sun_cos_max_);
}

bool SunLamp::sample_le(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                        EmittedPhoton* out) const {
  const Frame beam(axis_);
  if (bidirectional) {
    const Vec3 d = delta() ? beam.n : beam.to_world(sample_uniform_cone(u_dir, sun_cos_max_));
    const Frame across(d);
    const Vec2 q = sample_concentric_disk(u_pos);
    set_emitted_ray(
        frame.center + (across.t * q.x + across.b * q.y) * frame.radius - d * (2.0f * frame.radius),
        d, &out->ray);
    const float cone = delta() ? 1.0f : uniform_cone_pdf(sun_cos_max_);
    out->radiance = irradiance_ * cone;
    out->pdf_pos = scene_disc_pdf(frame);
    out->pdf_dir = out->direct_pdf = cone;
    out->cos_light = 1.0f;
    return true;
  }
  // The beam travels along the sun's axis (sample_li looks back along -axis).
  const Vec3 d =
      sun_cos_max_ < 1.0f ? beam.to_world(sample_uniform_cone(u_dir, sun_cos_max_)) : beam.n;
  const Vec2 q = sample_concentric_disk(u_pos);
  const Vec3 origin =
      frame.center + (beam.t * q.x + beam.b * q.y) * frame.radius - beam.n * (2.0f * frame.radius);
  set_emitted_ray(origin, d, &out->ray);
  out->power = irradiance_ * (kPi * frame.radius * frame.radius);
  return true;
}

bool SunLamp::sample_le_towards(const std::vector<BoundingSphere>& targets,
                                const PhotonFrame& frame, float u_pick, Vec2 u_pos, Vec2 u_dir,
                                Sampler&, EmittedPhoton* out) const {
  // A direction in the sun's disc, then a point of the targets' footprint across that
  // direction: E / (area density) per photon, as the unaimed beam's E pi R^2.
  const Frame beam(axis_);
  const Vec3 d =
      sun_cos_max_ < 1.0f ? beam.to_world(sample_uniform_cone(u_dir, sun_cos_max_)) : beam.n;
  const DiscMixture discs(d, targets);
  if (discs.empty()) return false;
  Vec3 p;
  float pdf;
  discs.sample(u_pick, u_pos, &p, &pdf);
  if (!(pdf > 0.0f)) return false;
  const float back = dot(frame.center, d) - 2.0f * frame.radius;
  set_emitted_ray(p + d * back, d, &out->ray);
  out->power = irradiance_ / pdf;
  return true;
}

float SunLamp::coverage(const std::vector<BoundingSphere>& targets, float scene_radius) const {
  if (targets.empty()) return 0.0f;
  const DiscMixture discs(axis_, targets);
  return std::min(1.0f, discs.total_area() / (kPi * scene_radius * scene_radius));
}

}  // namespace photon

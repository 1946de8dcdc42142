#include "photon/lights/world_light.h"

#include "photon/base/sampling.h"

namespace photon {

void ray_from_infinity(const PhotonFrame& frame, const Vec3& d, Vec2 u_pos, Ray* ray) {
  const Frame f(d);
  const Vec2 q = sample_concentric_disk(u_pos);
  set_emitted_ray(frame.center + (f.t * q.x + f.b * q.y) * frame.radius - d * (2.0f * frame.radius),
                  d, ray);
}

LightBounds WorldEmitter::bounds() const {
  LightBounds b;
  b.infinite = true;
  b.lo = b.hi = Vec3(0.0f);
  b.power = mean_power(color_);
  return b;
}

bool WorldEmitter::sample_li(const Vec3&, const LightSampleU& u, const PhotonFrame* bidirectional,
                             LightSample* out) const {
  if (!bidirectional) return false;  // reached by BSDF sampling only
  out->wi = sample_uniform_sphere(u.uv);
  out->distance = INFINITY;
  out->radiance = color_;
  out->direct_pdf = kInv4Pi;
  out->emission_pdf = kInv4Pi * scene_disc_pdf(*bidirectional);
  out->cos_light = 1.0f;
  out->surface_normal = Vec3(0.0f);
  return !is_black(color_);
}

bool WorldEmitter::sample_le(const PhotonFrame& frame, float, Vec2 u_pos, Vec2 u_dir,
                             bool bidirectional, EmittedPhoton* out) const {
  // Travelling along d, entering through a disc perpendicular to d that covers the scene.
  ray_from_infinity(frame, sample_uniform_sphere(u_dir), u_pos, &out->ray);
  if (!bidirectional) {
    out->power = power(frame.radius);
    return true;
  }
  out->radiance = color_;
  out->pdf_pos = scene_disc_pdf(frame);
  out->pdf_dir = out->direct_pdf = kInv4Pi;
  out->cos_light = 1.0f;
  return !is_black(color_);
}

}  // namespace photon

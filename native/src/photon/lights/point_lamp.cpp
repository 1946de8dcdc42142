#include "photon/lights/point_lamp.h"

#include "photon/base/sampling.h"
#include "photon/base/spherical_caps.h"
#include "photon/lights/photon_aim.h"

namespace photon {
namespace {

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

}  // namespace

std::unique_ptr<Lamp> make_point_lamp(LampDescription d) {
  return std::make_unique<PointLamp>(std::move(d));
}

PointLamp::PointLamp(LampDescription d) : Lamp(d.light->visibility, std::move(d.spectrum)) {
  const Light& l = *d.light;
  spot_ = l.type == LightType::kSpot;
  position_ = l.light_to_world.column(3);
  axis_ = normalize(-l.light_to_world.column(2));
  radius_ = std::max(l.radius, 0.0f);
  intensity_ = d.flux_color * kInv4Pi;
  area_ = kPi * radius_ * radius_;
  radiance_ = area_ > 0.0f ? intensity_ / area_ : Vec3(0.0f);
  if (!is_finite(radiance_) || (radius_ > 0.0f && !(area_ > 0.0f))) {
    // A radius whose disc area under- or overflows a float: a point for every ray.
    radius_ = area_ = 0.0f;
    radiance_ = Vec3(0.0f);
  }
  // Cycles: cos_half_spot_angle = cos(spot_size / 2), smooth = (1 - cos) * blend.
  const float half = std::clamp(l.spot_size, 1e-4f, kPi) * 0.5f;
  cos_half_spot_ = std::cos(half);
  spot_smooth_ = (1.0f - cos_half_spot_) * std::clamp(l.spot_blend, 0.0f, 1.0f);
  spot_cosine_ = l.spot_cosine_falloff;
  ies_ = std::move(d.ies);
  flux_ = intensity_ * (4.0f * kPi);
  if (ies_ && !spot_) {
    flux_ = intensity_ * ies_->integral();
  } else if (ies_) {
    // Phi = I * integral of attenuation over the cone, by the midpoint rule in (cos, phi).
    constexpr int kSteps = 512, kTurns = 128;
    const Frame f(axis_);
    double sum = 0.0;
    const float dc = (1.0f - cos_half_spot_) / kSteps;
    for (int i = 0; i < kSteps; ++i) {
      const float c = cos_half_spot_ + (i + 0.5f) * dc;
      const float s = std::sqrt(std::max(0.0f, 1 - c * c));
      for (int j = 0; j < kTurns; ++j) {
        const float phi = (j + 0.5f) * (2.0f * kPi / kTurns);
        sum += attenuation(f.to_world(Vec3(s * std::cos(phi), s * std::sin(phi), c)));
      }
    }
    flux_ = intensity_ * static_cast<float>(sum * dc * (2.0 * kPi / kTurns));
  } else if (spot_) {
    // Phi = I * 2 pi * integral of attenuation(cos theta) d(cos theta) over the cone.
    constexpr int kSteps = 512;
    double sum = 0.0;
    const float dc = (1.0f - cos_half_spot_) / kSteps;
    for (int i = 0; i < kSteps; ++i) {
      const float c = cos_half_spot_ + (i + 0.5f) * dc;
      const Frame f(axis_);
      sum += attenuation(f.to_world(Vec3(std::sqrt(std::max(0.0f, 1 - c * c)), 0, c)));
    }
    flux_ = intensity_ * static_cast<float>(2.0 * kPi * sum * dc);
  }
}

float PointLamp::attenuation(const Vec3& dir_from_light) const {
  if (!spot_ && !ies_) return 1.0f;
  const float profile = ies_ ? ies_->factor(dir_from_light) : 1.0f;
  return spot_ ? spot_attenuation(dir_from_light) * profile : profile;
}

float PointLamp::spot_attenuation(const Vec3& dir_from_light) const {
  const float c = dot(axis_, dir_from_light);
  if (c <= cos_half_spot_) return 0.0f;
  const float t = c - cos_half_spot_;
  const float falloff = spot_cosine_ ? c : 1.0f;
  if (spot_smooth_ > 0.0f && t < spot_smooth_) return falloff * smoothstep01(t / spot_smooth_);
  return falloff;
}

uint8_t PointLamp::flags() const {
  return kEmitterBidirectional | (sphere() ? 0 : kEmitterDeltaPosition);
}

Vec3 PointLamp::power(float) const {
  return flux_;
}

LightBounds PointLamp::extent() const {
  LightBounds b;
  b.lo = position_ - Vec3(radius_);
  b.hi = position_ + Vec3(radius_);
  if (!spot_) {
    b.cos_theta_o = -1.0f;  // every direction
    b.cos_theta_e = 0.0f;
  } else {
    // A spot's light leaves within its cone; a radius widens it by the disc's edge, so the
    // bound keeps the cone and lets the box carry the rest (theta_u in importance()).
    b.axis = axis_;
    b.cos_theta_o = 1.0f;
    b.cos_theta_e = cos_half_spot_;
  }
  return b;
}

float PointLamp::direction_pdf(const Vec3& d) const {
  if (!spot_) return ies_ ? ies_->pdf(d) : kInv4Pi;
  return dot(d, axis_) >= cos_half_spot_ ? uniform_cone_pdf(cos_half_spot_) : 0.0f;
}

bool PointLamp::sample_li(const Vec3& p, const LightSampleU& u, const PhotonFrame* bidirectional,
                          LightSample* out) const {
  out->surface_normal = Vec3(0.0f);
  if (bidirectional) {
    if (sphere()) return sample_sphere_li(p, u.uv, out);
    const Vec3 to_light = position_ - p;
    const float dist2 = length_squared(to_light);
    if (!(dist2 > 0.0f)) return false;
    out->distance = std::sqrt(dist2);
    out->wi = to_light / out->distance;
    out->radiance = intensity_;
    out->emission_pdf = kInv4Pi;
    if (spot_) {
      out->radiance *= attenuation(-out->wi);
      out->emission_pdf = uniform_cone_pdf(cos_half_spot_);
    } else if (ies_) {
      out->radiance *= attenuation(-out->wi);
      out->emission_pdf = direction_pdf(-out->wi);
    }
    out->direct_pdf = dist2;
    out->cos_light = 1.0f;
    return !is_black(out->radiance);
  }
  Vec3 q = position_;
  float cos_light = 1.0f;
  if (radius_ > 0.0f) {
    // A disc of the lamp's radius facing the shaded point (Cycles 3.x "sphere" light).
    const Vec3 n = normalize(p - position_);
    const Vec2 d = sample_concentric_disk(u.uv);
    const Frame frame(n);
    q = position_ + (frame.t * d.x + frame.b * d.y) * radius_;
    cos_light = -1.0f;  // computed below once the direction is known
  }
  const Vec3 to_light = q - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  const float dist = std::sqrt(dist2);
  out->wi = to_light / dist;
  out->distance = dist;
  if (radius_ > 0.0f) cos_light = std::max(0.0f, dot(-out->wi, normalize(p - position_)));
  float att = cos_light;
  if (spot_ || ies_) att *= attenuation(-out->wi);
  if (att <= 0.0f) return false;
  out->weight = intensity_ * (att / dist2);
  out->pdf = radius_ > 0.0f ? dist2 / (cos_light * area_) : 0.0f;
  return true;
}

bool PointLamp::sample_sphere_li(const Vec3& p, Vec2 u, LightSample* out) const {
  const Vec3 n = sample_uniform_sphere(u);
  const Vec3 to_light = position_ + n * radius_ - p;
  const float dist2 = length_squared(to_light);
  if (!(dist2 > 0.0f)) return false;
  out->distance = std::sqrt(dist2);
  out->wi = to_light / out->distance;
  // Points on the far side of the sphere (and all of it, seen from inside) face away.
  out->cos_light = dot(-out->wi, n);
  if (!(out->cos_light > 1e-7f)) return false;
  out->radiance = sphere_radiance(-out->wi);
  out->direct_pdf = dist2 / (out->cos_light * 4.0f * area_);
  out->emission_pdf = direction_pdf(-out->wi) / (2.0f * area_);
  return !is_black(out->radiance) && std::isfinite(out->direct_pdf);
}

bool PointLamp::eval_li(const Vec3& p, const Vec3& wi, LightHit* out) const {
  if (!has_area()) return false;
  // The disc of the lamp's radius facing p, which sample_li() draws from.
  const Vec3 n = normalize(p - position_);
  const float denom = dot(wi, n);
  if (!(denom < 0.0f)) return false;
  const float t = dot(position_ - p, n) / denom;
  if (!(t > 0.0f)) return false;
  const Vec3 d = p + wi * t - position_;
  if (!(length_squared(d) <= radius_ * radius_)) return false;
  const float cos_light = -denom;
  Vec3 le = radiance_;
  if (spot_ || ies_) le *= attenuation(-wi);
  out->radiance = le;
  out->distance = t;
  out->pdf = t * t / (cos_light * area_);
  return true;
}

bool PointLamp::intersect(const Ray& ray, float tmax, bool bidirectional, LightHit* out) const {
  if (radius_ <= 0.0f) return false;  // a point: never met
  const Vec3 oc = ray.origin - position_;
  const float b = dot(oc, ray.direction);
  const float c = length_squared(oc) - radius_ * radius_;
  const float disc = b * b - c;
  if (bidirectional) {
    if (!sphere()) return false;
    if (!(disc >= 0.0f) || !(c > 0.0f)) return false;  // missed, or from inside the sphere
    const float t = -b - std::sqrt(disc);
    if (!(t > ray.tmin) || !(t < tmax)) return false;
    const Vec3 n = (ray.origin + ray.direction * t - position_) / radius_;
    out->cos_light = dot(-ray.direction, n);
    if (!(out->cos_light > 1e-7f)) return false;
    out->radiance = sphere_radiance(-ray.direction);
    out->distance = t;
    out->direct_pdf = 1.0f / (4.0f * area_);
    out->emission_pdf = direction_pdf(-ray.direction) / (2.0f * area_);
    return !is_black(out->radiance);
  }
  // Camera and glossy rays see the sphere, from inside too.
  if (disc < 0.0f) return false;
  const float s = std::sqrt(disc);
  float t = -b - s;
  if (t <= ray.tmin) t = -b + s;
  if (t <= ray.tmin || t >= tmax) return false;
  Vec3 le = radiance_;
  if (spot_ || ies_) le *= attenuation(-ray.direction);
  out->radiance = le;
  out->distance = t;
  return true;
}

bool PointLamp::sample_le(const PhotonFrame&, float, Vec2 u_pos, Vec2 u_dir, bool bidirectional,
                          EmittedPhoton* out) const {
  if (bidirectional) {
    if (sphere()) return emit_from_sphere(u_pos, u_dir, out);
    const Vec3 d = sample_direction(u_dir);
    set_emitted_ray(position_, d, &out->ray);
    out->radiance = spot_ || ies_ ? intensity_ * attenuation(d) : intensity_;
    out->pdf_pos = out->direct_pdf = out->cos_light = 1.0f;
    out->pdf_dir = spot_ ? uniform_cone_pdf(cos_half_spot_) : direction_pdf(d);
    return (!spot_ && !ies_) || !is_black(out->radiance);
  }
  if (ies_ && !spot_) {
    // Directions from the profile's table; a radius emits from the disc facing them.
    float pdf = 0.0f;
    const Vec3 d = ies_->sample(u_dir, &pdf);
    const float att = attenuation(d);
    if (!(att > 0.0f) || !(pdf > 0.0f)) return false;
    Vec3 origin = position_;
    if (radius_ > 0.0f) {
      const Vec2 q = sample_concentric_disk(u_pos);
      const Frame f(d);
      origin += (f.t * q.x + f.b * q.y) * radius_;
    }
    set_emitted_ray(origin, d, &out->ray);
    out->power = intensity_ * (att / pdf);
    return true;
  }
  if (!spot_) {
    if (radius_ > 0.0f) {
      const Vec3 n = sample_uniform_sphere(u_pos);
      const Vec3 d = Frame(n).to_world(sample_cosine_hemisphere(u_dir));
      set_emitted_ray(position_ + n * radius_, d, &out->ray);
    } else {
      set_emitted_ray(position_, sample_uniform_sphere(u_dir), &out->ray);
    }
    out->power = intensity_ * (4.0f * kPi);
    return true;
  }
  const Vec3 d = Frame(axis_).to_world(sample_uniform_cone(u_dir, cos_half_spot_));
  Vec3 origin = position_;
  if (radius_ > 0.0f) {  // the disc of the lamp's radius facing the lit direction
    const Vec2 q = sample_concentric_disk(u_pos);
    const Frame f(d);
    origin += (f.t * q.x + f.b * q.y) * radius_;
  }
  set_emitted_ray(origin, d, &out->ray);
  out->power = intensity_ * (attenuation(d) / uniform_cone_pdf(cos_half_spot_));
  return true;
}

Vec3 PointLamp::sample_direction(Vec2 u) const {
  if (spot_) return Frame(axis_).to_world(sample_uniform_cone(u, cos_half_spot_));
  if (ies_) {
    float pdf;
    return ies_->sample(u, &pdf);
  }
  return sample_uniform_sphere(u);
}

bool PointLamp::emit_from_sphere(Vec2 u_pos, Vec2 u_dir, EmittedPhoton* out) const {
  const Vec3 d = sample_direction(u_dir);
  // The hemisphere facing d: a uniform point of it, d itself at the pole.
  const Vec3 n = Frame(d).to_world(sample_uniform_cone(u_pos, 0.0f));
  set_emitted_ray(position_ + n * radius_, d, &out->ray);
  out->radiance = sphere_radiance(d);
  out->pdf_pos = 1.0f / (2.0f * area_);  // the hemisphere's area is 2 pi r^2
  out->pdf_dir = direction_pdf(d);
  out->direct_pdf = 1.0f / (4.0f * area_);
  out->cos_light = dot(n, d);
  return out->cos_light > 0.0f && !is_black(out->radiance);
}

bool PointLamp::sample_le_towards(const std::vector<BoundingSphere>& targets, const PhotonFrame&,
                                  float u_pick, Vec2 u_pos, Vec2 u_dir, Sampler&,
                                  EmittedPhoton* out) const {
  Vec3 d;
  float pdf;
  if (radius_ > 0.0f && !spot_) {
    // Only points of the sphere that see a target, and only directions into the hemisphere
    // above them (area density times solid-angle density).
    Vec3 n;
    if (!SphereLightAim(position_, radius_, targets).sample(u_pick, u_pos, u_dir, &n, &d, &pdf))
      return false;
    const float cos_n = dot(d, n);
    if (cos_n <= 0.0f) return false;
    set_emitted_ray(position_ + n * radius_, d, &out->ray);
    out->power = radiance_ * (cos_n * (ies_ ? attenuation(d) : 1.0f) / pdf);
    return true;
  }
  // Directions inside both the lamp's cone and a target's; a spot with a radius emits from a
  // disc, so its targets are widened by that radius.
  const Cap region = spot_ ? Cap(axis_, std::acos(double(cos_half_spot_))) : Cap::whole_sphere();
  if (!ConeMixture(position_, targets, region, radius_).sample(u_pick, u_dir, &d, &pdf))
    return false;
  Vec3 origin = position_;
  if (radius_ > 0.0f) {
    const Vec2 q = sample_concentric_disk(u_pos);
    const Frame f(d);
    origin += (f.t * q.x + f.b * q.y) * radius_;
  }
  const float att = attenuation(d);
  if (att <= 0.0f) return false;
  set_emitted_ray(origin, d, &out->ray);
  out->power = intensity_ * (att / pdf);
  return true;
}

float PointLamp::coverage(const std::vector<BoundingSphere>& targets, float) const {
  if (targets.empty()) return 0.0f;
  // The share of the lamp's cone (seen from its centre) that heads into targets.
  const Cap region = spot_ ? Cap(axis_, std::acos(double(cos_half_spot_))) : Cap::whole_sphere();
  return ConeMixture(position_, targets, region, radius_).coverage();
}

}  // namespace photon

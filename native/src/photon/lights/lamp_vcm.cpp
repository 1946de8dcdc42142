// Blender lamps for bidirectional estimators (emission_pdf.h): the densities of an emitted ray
// and of a light sample, in the units LightSet::sample uses, so the strategies of a
// bidirectional path tracer estimate the same light as direct lighting does:
//  - point of radius 0: a uniform direction, intensity I (W/sr);
//  - spot of radius 0: a uniform direction in the cone, I times Cycles' cone attenuation;
//  - point or spot with a radius r: a Lambertian sphere of radiance L = I / (pi r^2) (times the
//    spot's attenuation along the direction of travel), which has the intensity I of the point
//    in every direction and which camera rays meet, as LightSet::intersect_one sees it. An
//    emitted ray takes its direction first (uniform, or uniform in the cone) and then a uniform
//    point on the hemisphere facing it (1 / (2 pi r^2)); a light sample takes a uniform point on
//    the whole sphere (1 / (4 pi r^2)), of which the half facing the receiver lights it;
//  - area: a uniform point (1 / A) and a cosine-distributed direction (cos / pi), radiance L;
//  - sun: a point uniform on the scene's disc (1 / (pi R^2)) and a direction uniform in the
//    sun's cone, radiance E / (solid angle of the cone) so the disc gives irradiance E; a sun
//    of angle 0 is a parallel beam of irradiance E.
#include "photon/base/sampling.h"
#include "photon/lights/lights.h"

namespace photon {
namespace {

void set_ray(const Vec3& origin, const Vec3& direction, Ray* ray) {
  ray->origin = origin;
  ray->direction = direction;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
}

float disc_pdf(float scene_radius) {
  return 1.0f / (kPi * scene_radius * scene_radius);
}

}  // namespace

bool LightSet::sphere_lamp(const Prepared& l) {
  return (l.type == LightType::kPoint || l.type == LightType::kSpot) && l.radius > 0.0f &&
         l.area > 0.0f;
}

float LightSet::lamp_direction_pdf(const Prepared& l, const Vec3& d) {
  if (l.type == LightType::kPoint) return kInv4Pi;
  return dot(d, l.axis) >= l.cos_half_spot ? uniform_cone_pdf(l.cos_half_spot) : 0.0f;
}

Vec3 LightSet::sphere_radiance(const Prepared& l, const Vec3& d) {
  return l.type == LightType::kSpot ? l.radiance * spot_attenuation(l, d) : l.radiance;
}

uint8_t LightSet::vcm_flags(size_t index) const {
  const Prepared& l = lights_[index];
  switch (l.type) {
    case LightType::kPoint:
    case LightType::kSpot:
      return kVcmSupported | (sphere_lamp(l) ? 0 : kVcmDeltaPosition);
    case LightType::kArea:
      return kVcmSupported;
    case LightType::kSun:
      return kVcmSupported | kVcmInfinite | (l.sun_cos_max >= 1.0f ? kVcmDeltaDirection : 0);
  }
  return 0;
}

bool LightSet::emit_vcm(size_t index, const Vec3& scene_center, float scene_radius, Vec2 u_pos,
                        Vec2 u_dir, EmissionSample* out) const {
  const Prepared& l = lights_[index];
  if (sphere_lamp(l)) {
    const Vec3 d = l.type == LightType::kPoint
                       ? sample_uniform_sphere(u_dir)
                       : Frame(l.axis).to_world(sample_uniform_cone(u_dir, l.cos_half_spot));
    // The hemisphere facing d: a uniform point of it, d itself at the pole.
    const Vec3 n = Frame(d).to_world(sample_uniform_cone(u_pos, 0.0f));
    set_ray(l.position + n * l.radius, d, &out->ray);
    out->radiance = sphere_radiance(l, d);
    out->pdf_pos = 1.0f / (2.0f * l.area);  // the hemisphere's area is 2 pi r^2
    out->pdf_dir = lamp_direction_pdf(l, d);
    out->direct_pdf = 1.0f / (4.0f * l.area);
    out->cos_light = dot(n, d);
    return out->cos_light > 0.0f && !is_black(out->radiance);
  }
  switch (l.type) {
    case LightType::kPoint: {
      set_ray(l.position, sample_uniform_sphere(u_dir), &out->ray);
      out->radiance = l.intensity;
      out->pdf_pos = out->direct_pdf = out->cos_light = 1.0f;
      out->pdf_dir = kInv4Pi;
      return true;
    }
    case LightType::kSpot: {
      const Vec3 d = Frame(l.axis).to_world(sample_uniform_cone(u_dir, l.cos_half_spot));
      set_ray(l.position, d, &out->ray);
      out->radiance = l.intensity * spot_attenuation(l, d);
      out->pdf_pos = out->direct_pdf = out->cos_light = 1.0f;
      out->pdf_dir = uniform_cone_pdf(l.cos_half_spot);
      return !is_black(out->radiance);
    }
    case LightType::kArea: {
      Vec3 q;
      if (l.shape == AreaShape::kRectangle) {
        q = l.position + l.half_u * (2.0f * u_pos.x - 1.0f) + l.half_v * (2.0f * u_pos.y - 1.0f);
      } else {
        const Vec2 d = sample_concentric_disk(u_pos);
        q = l.position + l.half_u * d.x + l.half_v * d.y;
      }
      const Vec3 local = sample_cosine_hemisphere(u_dir);
      set_ray(q, Frame(l.axis).to_world(local), &out->ray);
      out->radiance = l.radiance;
      out->pdf_pos = out->direct_pdf = 1.0f / l.area;
      out->cos_light = local.z;
      out->pdf_dir = local.z * kInvPi;
      return local.z > 0.0f;
    }
    case LightType::kSun: {
      const Frame beam(l.axis);
      const bool delta = l.sun_cos_max >= 1.0f;
      const Vec3 d = delta ? beam.n : beam.to_world(sample_uniform_cone(u_dir, l.sun_cos_max));
      const Frame across(d);
      const Vec2 q = sample_concentric_disk(u_pos);
      set_ray(scene_center + (across.t * q.x + across.b * q.y) * scene_radius -
                  d * (2.0f * scene_radius),
              d, &out->ray);
      const float cone = delta ? 1.0f : uniform_cone_pdf(l.sun_cos_max);
      out->radiance = l.irradiance * cone;
      out->pdf_pos = disc_pdf(scene_radius);
      out->pdf_dir = out->direct_pdf = cone;
      out->cos_light = 1.0f;
      return true;
    }
  }
  return false;
}

bool LightSet::illuminate_vcm(size_t index, float scene_radius, const Vec3& p, Vec2 u,
                              Illumination* out) const {
  const Prepared& l = lights_[index];
  out->surface_normal = Vec3(0.0f);
  if (sphere_lamp(l)) {
    const Vec3 n = sample_uniform_sphere(u);
    const Vec3 to_light = l.position + n * l.radius - p;
    const float dist2 = length_squared(to_light);
    if (!(dist2 > 0.0f)) return false;
    out->distance = std::sqrt(dist2);
    out->wi = to_light / out->distance;
    // Points on the far side of the sphere (and all of it, seen from inside) face away.
    out->cos_light = dot(-out->wi, n);
    if (!(out->cos_light > 1e-7f)) return false;
    out->radiance = sphere_radiance(l, -out->wi);
    out->direct_pdf = dist2 / (out->cos_light * 4.0f * l.area);
    out->emission_pdf = lamp_direction_pdf(l, -out->wi) / (2.0f * l.area);
    return !is_black(out->radiance) && std::isfinite(out->direct_pdf);
  }
  switch (l.type) {
    case LightType::kPoint:
    case LightType::kSpot: {
      const Vec3 to_light = l.position - p;
      const float dist2 = length_squared(to_light);
      if (!(dist2 > 0.0f)) return false;
      out->distance = std::sqrt(dist2);
      out->wi = to_light / out->distance;
      out->radiance = l.intensity;
      out->emission_pdf = kInv4Pi;
      if (l.type == LightType::kSpot) {
        out->radiance *= spot_attenuation(l, -out->wi);
        out->emission_pdf = uniform_cone_pdf(l.cos_half_spot);
      }
      out->direct_pdf = dist2;
      out->cos_light = 1.0f;
      return !is_black(out->radiance);
    }
    case LightType::kArea: {
      Vec3 q;
      if (l.shape == AreaShape::kRectangle) {
        q = l.position + l.half_u * (2.0f * u.x - 1.0f) + l.half_v * (2.0f * u.y - 1.0f);
      } else {
        const Vec2 d = sample_concentric_disk(u);
        q = l.position + l.half_u * d.x + l.half_v * d.y;
      }
      const Vec3 to_light = q - p;
      const float dist2 = length_squared(to_light);
      if (!(dist2 > 0.0f)) return false;
      out->distance = std::sqrt(dist2);
      out->wi = to_light / out->distance;
      const float cos_light = dot(-out->wi, l.axis);
      if (!(cos_light > 1e-7f)) return false;
      out->radiance = l.radiance;
      out->cos_light = cos_light;
      out->direct_pdf = dist2 / (cos_light * l.area);
      out->emission_pdf = cos_light * kInvPi / l.area;
      return std::isfinite(out->direct_pdf);
    }
    case LightType::kSun: {
      const bool delta = l.sun_cos_max >= 1.0f;
      const Frame frame(-l.axis);
      out->wi = delta ? -l.axis : frame.to_world(sample_uniform_cone(u, l.sun_cos_max));
      out->distance = INFINITY;
      const float cone = delta ? 1.0f : uniform_cone_pdf(l.sun_cos_max);
      out->radiance = l.irradiance * cone;
      out->direct_pdf = cone;
      out->emission_pdf = cone * disc_pdf(scene_radius);
      out->cos_light = 1.0f;
      return true;
    }
  }
  return false;
}

bool LightSet::hit_vcm(size_t index, float scene_radius, const Ray& ray, float tmax,
                       EmitterHit* out) const {
  const Prepared& l = lights_[index];
  if (l.type == LightType::kSun) {
    if (l.sun_cos_max >= 1.0f || tmax < INFINITY) return false;
    if (!(dot(-ray.direction, l.axis) >= l.sun_cos_max)) return false;
    const float cone = uniform_cone_pdf(l.sun_cos_max);
    out->radiance = l.irradiance * cone;
    out->distance = INFINITY;
    out->direct_pdf = cone;
    out->emission_pdf = cone * disc_pdf(scene_radius);
    return true;
  }
  if (sphere_lamp(l)) {
    const Vec3 oc = ray.origin - l.position;
    const float b = dot(oc, ray.direction);
    const float c = length_squared(oc) - l.radius * l.radius;
    const float disc = b * b - c;
    if (!(disc >= 0.0f) || !(c > 0.0f)) return false;  // missed, or from inside the sphere
    const float t = -b - std::sqrt(disc);
    if (!(t > ray.tmin) || !(t < tmax)) return false;
    const Vec3 n = (ray.origin + ray.direction * t - l.position) / l.radius;
    out->cos_light = dot(-ray.direction, n);
    if (!(out->cos_light > 1e-7f)) return false;
    out->radiance = sphere_radiance(l, -ray.direction);
    out->distance = t;
    out->direct_pdf = 1.0f / (4.0f * l.area);
    out->emission_pdf = lamp_direction_pdf(l, -ray.direction) / (2.0f * l.area);
    return !is_black(out->radiance);
  }
  if (l.type != LightType::kArea) return false;  // points: never met
  const float denom = dot(ray.direction, l.axis);
  if (!(denom < 0.0f)) return false;  // its back is dark
  const float t = dot(l.position - ray.origin, l.axis) / denom;
  if (!(t > ray.tmin) || !(t < tmax)) return false;
  const Vec3 d = ray.origin + ray.direction * t - l.position;
  const float su = dot(d, l.half_u) / length_squared(l.half_u);
  const float sv = dot(d, l.half_v) / length_squared(l.half_v);
  const bool inside = l.shape == AreaShape::kRectangle
                          ? std::fabs(su) <= 1.0f && std::fabs(sv) <= 1.0f
                          : su * su + sv * sv <= 1.0f;
  if (!inside) return false;
  out->radiance = l.radiance;
  out->distance = t;
  out->direct_pdf = 1.0f / l.area;
  out->emission_pdf = -denom * kInvPi / l.area;
  out->cos_light = -denom;
  return true;
}

}  // namespace photon

// Photon emission from Blender's lights (Jensen 2001, sec. 5.1), in the same units as
// LightSet::sample so photon-mapped and directly sampled light agree:
//  - point of radius 0: uniform directions, flux 4 pi I; with a radius r, a uniform point on the
//    sphere and a cosine-distributed direction around its normal (radiance I / (pi r^2));
//  - spot: uniform directions inside the cone, weighted by Cycles' cone attenuation;
//  - area: a uniform point and a cosine-distributed direction down the light's axis, pi L A;
//  - sun: a parallel beam along the light's axis through a disc that covers the scene, flux
//    E pi R^2.
// Caustic photons (emit_towards) go only where the light's emission and a specular target's
// cone overlap: spot cone ∩ target cone, an area light's hemisphere ∩ target cone, the side of
// a sphere light facing the target, the sun's disc of directions times the target's footprint.
#include "photon/lights/photon_aim.h"
#include "photon/lights/lights.h"
#include "photon/base/sampling.h"
#include "photon/base/spherical_caps.h"

namespace photon {
namespace {

Vec3 area_light_point(const Vec3& center, const Vec3& half_u, const Vec3& half_v, AreaShape shape,
                      Vec2 u) {
  if (shape == AreaShape::kRectangle)
    return center + half_u * (2.0f * u.x - 1.0f) + half_v * (2.0f * u.y - 1.0f);
  const Vec2 d = sample_concentric_disk(u);
  return center + half_u * d.x + half_v * d.y;
}

void set_ray(const Vec3& origin, const Vec3& direction, Ray* ray) {
  ray->origin = origin;
  ray->direction = direction;
  ray->tmin = 0.0f;
  ray->tmax = INFINITY;
}

}  // namespace

Vec3 LightSet::power(size_t index, float scene_radius) const {
  const Prepared& l = lights_[index];
  switch (l.type) {
    case LightType::kPoint:
      return l.intensity * (4.0f * kPi);
    case LightType::kSpot: {
      // Phi = I * 2 pi * integral of attenuation(cos theta) d(cos theta) over the cone.
      constexpr int kSteps = 512;
      double sum = 0.0;
      const float dc = (1.0f - l.cos_half_spot) / kSteps;
      for (int i = 0; i < kSteps; ++i) {
        const float c = l.cos_half_spot + (i + 0.5f) * dc;
        const Frame f(l.axis);
        sum += spot_attenuation(l, f.to_world(Vec3(std::sqrt(std::max(0.0f, 1 - c * c)), 0, c)));
      }
      return l.intensity * static_cast<float>(2.0 * kPi * sum * dc);
    }
    case LightType::kSun:
      return l.irradiance * (kPi * scene_radius * scene_radius);
    case LightType::kArea:
      return l.radiance * (kPi * l.area);
  }
  return Vec3(0.0f);
}

void LightSet::emit(size_t index, const Vec3& scene_center, float scene_radius, Vec2 u_pos,
                    Vec2 u_dir, EmittedPhoton* out) const {
  const Prepared& l = lights_[index];
  switch (l.type) {
    case LightType::kPoint: {
      if (l.radius > 0.0f) {
        const Vec3 n = sample_uniform_sphere(u_pos);
        const Vec3 d = Frame(n).to_world(sample_cosine_hemisphere(u_dir));
        set_ray(l.position + n * l.radius, d, &out->ray);
      } else {
        set_ray(l.position, sample_uniform_sphere(u_dir), &out->ray);
      }
      out->power = l.intensity * (4.0f * kPi);
      return;
    }
    case LightType::kSpot: {
      const Vec3 d = Frame(l.axis).to_world(sample_uniform_cone(u_dir, l.cos_half_spot));
      Vec3 origin = l.position;
      if (l.radius > 0.0f) {  // the disc of the light's radius facing the lit direction
        const Vec2 q = sample_concentric_disk(u_pos);
        const Frame f(d);
        origin += (f.t * q.x + f.b * q.y) * l.radius;
      }
      set_ray(origin, d, &out->ray);
      out->power = l.intensity * (spot_attenuation(l, d) / uniform_cone_pdf(l.cos_half_spot));
      return;
    }
    case LightType::kSun: {
      // The beam travels along the light's axis (LightSet::sample looks back along -axis).
      const Frame beam(l.axis);
      const Vec3 d =
          l.sun_cos_max < 1.0f ? beam.to_world(sample_uniform_cone(u_dir, l.sun_cos_max)) : beam.n;
      const Vec2 q = sample_concentric_disk(u_pos);
      const Vec3 origin = scene_center + (beam.t * q.x + beam.b * q.y) * scene_radius -
                          beam.n * (2.0f * scene_radius);
      set_ray(origin, d, &out->ray);
      out->power = l.irradiance * (kPi * scene_radius * scene_radius);
      return;
    }
    case LightType::kArea: {
      const Vec3 q = area_light_point(l.position, l.half_u, l.half_v, l.shape, u_pos);
      const Vec3 d = Frame(l.axis).to_world(sample_cosine_hemisphere(u_dir));
      set_ray(q, d, &out->ray);
      out->power = l.radiance * (kPi * l.area);
      return;
    }
  }
}

// The cone of directions a light emits into: a spot's cone, an area light's hemisphere.
Cap LightSet::emission_region(const Prepared& l) {
  if (l.type == LightType::kSpot) return Cap(l.axis, std::acos(double(l.cos_half_spot)));
  if (l.type == LightType::kArea) return Cap(l.axis, 0.5 * Cap::kPiD);
  return Cap::whole_sphere();
}

bool LightSet::emit_towards(size_t index, const std::vector<BoundingSphere>& targets,
                            const Vec3& scene_center, float scene_radius, float u_pick, Vec2 u_pos,
                            Vec2 u_dir, EmittedPhoton* out) const {
  const Prepared& l = lights_[index];
  Vec3 d;
  float pdf;
  switch (l.type) {
    case LightType::kPoint:
    case LightType::kSpot: {
      if (l.radius > 0.0f && l.type == LightType::kPoint) {
        // Only points of the sphere that see a target, and only directions into the
        // hemisphere above them (area density times solid-angle density).
        Vec3 n;
        if (!SphereLightAim(l.position, l.radius, targets)
                 .sample(u_pick, u_pos, u_dir, &n, &d, &pdf))
          return false;
        const float cos_n = dot(d, n);
        if (cos_n <= 0.0f) return false;
        set_ray(l.position + n * l.radius, d, &out->ray);
        out->power = l.radiance * (cos_n / pdf);
        return true;
      }
      // Directions inside both the light's cone and a target's; a spot with a radius emits from
      // a disc, so its targets are widened by that radius.
      if (!ConeMixture(l.position, targets, emission_region(l), l.radius)
               .sample(u_pick, u_dir, &d, &pdf))
        return false;
      Vec3 origin = l.position;
      if (l.radius > 0.0f) {
        const Vec2 q = sample_concentric_disk(u_pos);
        const Frame f(d);
        origin += (f.t * q.x + f.b * q.y) * l.radius;
      }
      const float attenuation = l.type == LightType::kSpot ? spot_attenuation(l, d) : 1.0f;
      if (attenuation <= 0.0f) return false;
      set_ray(origin, d, &out->ray);
      out->power = l.intensity * (attenuation / pdf);
      return true;
    }
    case LightType::kSun: {
      // A direction in the sun's disc, then a point of the targets' footprint across that
      // direction: E / (area density) per photon, as the unaimed beam's E pi R^2.
      const Frame beam(l.axis);
      d = l.sun_cos_max < 1.0f ? beam.to_world(sample_uniform_cone(u_dir, l.sun_cos_max)) : beam.n;
      const DiscMixture discs(d, targets);
      if (discs.empty()) return false;
      Vec3 p;
      discs.sample(u_pick, u_pos, &p, &pdf);
      if (!(pdf > 0.0f)) return false;
      const float back = dot(scene_center, d) - 2.0f * scene_radius;
      set_ray(p + d * back, d, &out->ray);
      out->power = l.irradiance / pdf;
      return true;
    }
    case LightType::kArea: {
      // One-sided: directions in the hemisphere below the light that head into a target, so
      // targets behind its plane get nothing and those partly behind only their facing part.
      const Vec3 q = area_light_point(l.position, l.half_u, l.half_v, l.shape, u_pos);
      if (!ConeMixture(q, targets, emission_region(l)).sample(u_pick, u_dir, &d, &pdf))
        return false;
      const float cos_l = dot(d, l.axis);
      if (cos_l <= 0.0f) return false;
      set_ray(q, d, &out->ray);
      out->power = l.radiance * (cos_l * l.area / pdf);
      return true;
    }
  }
  return false;
}

float LightSet::coverage(size_t index, const std::vector<BoundingSphere>& targets,
                         float scene_radius) const {
  const Prepared& l = lights_[index];
  if (targets.empty()) return 0.0f;
  if (l.type == LightType::kSun) {
    const DiscMixture discs(l.axis, targets);
    return std::min(1.0f, discs.total_area() / (kPi * scene_radius * scene_radius));
  }
  // The share of the light's cone (seen from its centre) that heads into targets; zero for an
  // area light whose targets are all behind it.
  return ConeMixture(l.position, targets, emission_region(l), l.radius).coverage();
}

}  // namespace photon

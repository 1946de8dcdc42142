#include "photon/render/shadow_ray.h"

#include <cmath>

#include "photon/render/material_eval.h"

namespace photon {

Vec3 transparent_weight(const Bsdf& bsdf) {
  Vec3 t(0.0f);
  for (int i = 0; i < bsdf.lobe_count(); ++i)
    if (bsdf.lobe(i).type == LobeType::kTransparent) t += bsdf.lobe(i).weight;
  return t;
}

Vec3 straight_transmittance(const Accel& accel, const TextureSet* textures,
                            const SurfaceInteraction& si, const Vec3& direction) {
  if (!si.mat || !si.mat->may_be_transparent()) return Vec3(0.0f);
  ShadeRay ray;
  ray.flags = kRayShadow;
  const Vec3 t = transparent_weight(shade_surface(si, -direction, accel, textures, ray).bsdf);
  // Weights are clamped inputs times mix factors: at most 1 unless an Add Shader sums two.
  return is_finite(t) ? max(t, Vec3(0.0f)) : Vec3(0.0f);
}

Ray ray_past(const Ray& ray, const SurfaceInteraction& si, float length_scale) {
  Ray next = ray;
  next.origin = offset_ray_origin(si.p, si.ng, ray.direction, length_scale);
  next.tmin = 0.0f;
  if (std::isfinite(ray.tmax)) {
    const Vec3 end = ray.origin + ray.direction * ray.tmax;
    next.tmax = std::max(0.0f, dot(end - next.origin, ray.direction));
  }
  return next;
}

Vec3 shadow_transmittance(const Accel& accel, const TextureSet* textures, const Ray& ray,
                          int max_crossings) {
  if (!accel.has_transparent_shadows())
    return accel.occluded(ray, kVisibleShadow) ? Vec3(0.0f) : Vec3(1.0f);
  if (accel.occluded(ray, kShadowOpaque)) return Vec3(0.0f);
  // The transparent casters in order along the ray (the product does not depend on the order,
  // but the walk needs each next hit, and an opaque triangle among them ends it early).
  Vec3 t(1.0f);
  Ray r = ray;
  for (int crossed = 0;; ++crossed) {
    Hit hit;
    if (!accel.intersect(r, kShadowTransparent, &hit)) return t;
    if (crossed >= max_crossings) return Vec3(0.0f);
    const SurfaceInteraction si = accel.interaction(hit);
    t *= straight_transmittance(accel, textures, si, r.direction);
    if (is_black(t)) return Vec3(0.0f);
    r = ray_past(r, si, accel.length_scale());
    if (!(r.tmax > 0.0f)) return t;
  }
}

}  // namespace photon

#include "photon/lights/direct_lighting.h"

#include <cmath>

#include "photon/lights/emissive_mesh.h"
#include "photon/render/material_eval.h"

namespace photon {
namespace {

// Veach 1997, eq. 9.13 with beta = 2. Densities above ~1.8e19 (a light of tiny area seen from
// afar) overflow when squared: then the same weight is taken in ratio form, so it stays 1 for
// the far larger density instead of inf / inf = NaN, which dropped the light sample.
inline float power_heuristic(float f, float g) {
  const float f2 = f * f, g2 = g * g;
  if (std::isfinite(f2 + g2)) return f2 + g2 > 0.0f ? f2 / (f2 + g2) : 0.0f;
  if (!(f > 0.0f) || std::isnan(g)) return 0.0f;
  if (!std::isfinite(f)) return std::isfinite(g) ? 1.0f : 0.5f;
  const float r = g / f;
  return 1.0f / (1.0f + r * r);
}

bool unoccluded(const RenderContext& context, const SurfaceInteraction& si, const Vec3& wi,
                float distance) {
  Ray shadow;
  shadow.origin = offset_ray_origin(si.p, si.ng, wi, context.accel->length_scale());
  shadow.direction = wi;
  shadow.tmax = std::isfinite(distance) ? distance * (1.0f - 1e-4f) : INFINITY;
  return !context.accel->occluded(shadow, kVisibleShadow);
}

// Visibility of a sampled light point. A point on an emissive triangle is scene geometry: the
// shadow ray must stop short of that surface, or it ends inside it and the light occludes
// itself (everywhere the offset exceeds the tmax margin: nearly all light samples).
bool unoccluded(const RenderContext& context, const SurfaceInteraction& si, const LightSample& ls) {
  if (!(length_squared(ls.surface_normal) > 0.0f) || !std::isfinite(ls.distance))
    return unoccluded(context, si, ls.wi, ls.distance);
  const Ray shadow = shadow_ray_between(si.p, si.ng, si.p + ls.wi * ls.distance, ls.surface_normal,
                                        context.accel->length_scale());
  return !context.accel->occluded(shadow, kVisibleShadow);
}

// f |cos| towards a sampled light direction, and the BSDF's density of sampling it.
Vec3 bsdf_towards(const Bsdf& bsdf, const Vec3& wo, const Vec3& wi, uint8_t lobes, float* pdf) {
  const Vec3 f = bsdf.eval(wo, wi, lobes);
  *pdf = bsdf.pdf(wo, wi, lobes);
  return f * std::fabs(dot(bsdf.frame().n, wi));
}

// Light sample of light i (or of the emissive meshes), weighted against BSDF sampling.
Vec3 light_sample_term(const RenderContext& context, const SurfaceInteraction& si, const Bsdf& bsdf,
                       const Vec3& wo, uint8_t lobes, const LightSample& ls) {
  float pdf_bsdf;
  const Vec3 f_cos = bsdf_towards(bsdf, wo, ls.wi, lobes, &pdf_bsdf);
  if (is_black(f_cos) || !unoccluded(context, si, ls)) return Vec3(0.0f);
  const float w = ls.pdf > 0.0f ? power_heuristic(ls.pdf, pdf_bsdf) : 1.0f;
  return f_cos * ls.weight * w;
}

}  // namespace

Vec3 direct_radiance(const RenderContext& context, const SurfaceInteraction& si, const Bsdf& bsdf,
                     const Vec3& wo, Sampler& sampler, uint8_t lobes) {
  Vec3 l(0.0f);
  lobes &= kLobeDiffuse | kLobeGlossy;  // delta lobes reach lights by ray tracing
  if (!(bsdf.flags() & lobes)) return l;
  const LightSet& lights = *context.lights;
  BsdfSample bs;
  for (size_t i = 0; i < lights.size(); ++i) {
    LightSample ls;
    const Vec2 u_light = sampler.get_2d();
    if (lights.sample(i, si.p, u_light, &ls))
      l += light_sample_term(context, si, bsdf, wo, lobes, ls);
    if (!lights.has_area(i)) continue;
    // BSDF sample, weighted against the light sample.
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (!bsdf.sample(wo, u_lobe, u, lobes, &bs)) continue;
    Vec3 le;
    float distance, pdf_light;
    if (!lights.eval(i, si.p, bs.wi, &le, &distance, &pdf_light)) continue;
    if (!unoccluded(context, si, bs.wi, distance)) continue;
    l += le * bs.weight * power_heuristic(bs.pdf, pdf_light);
  }

  const EmissiveMeshes* emissive = context.emissive;
  if (emissive && !emissive->empty()) {
    LightSample ls;
    const float u_pick = sampler.get_1d();
    const Vec2 u_point = sampler.get_2d();
    if (emissive->sample(si.p, u_pick, u_point, &ls))
      l += light_sample_term(context, si, bsdf, wo, lobes, ls);
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (bsdf.sample(wo, u_lobe, u, lobes, &bs)) {
      Ray ray;
      ray.origin = offset_ray_origin(si.p, si.ng, bs.wi, context.accel->length_scale());
      ray.direction = bs.wi;
      Hit hit;
      if (context.accel->intersect(ray, kVisibleShadow, &hit)) {
        const SurfaceInteraction light_si = context.accel->interaction(hit);
        const float pdf_light =
            emissive->pdf(hit.instance, hit.primitive, hit.t, dot(bs.wi, light_si.ng));
        if (pdf_light > 0.0f)
          l += emitted_radiance(*light_si.mat, light_si, context.textures) * bs.weight *
               power_heuristic(bs.pdf, pdf_light);
      }
    }
  }

  // A uniform world is a light from every direction: a BSDF sample and one shadow ray.
  const Vec3& world = context.scene->world.color;
  if (!is_black(world)) {
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (bsdf.sample(wo, u_lobe, u, lobes, &bs) && unoccluded(context, si, bs.wi, INFINITY))
      l += world * bs.weight;
  }
  return is_finite(l) ? l : Vec3(0.0f);
}

Vec3 direct_radiance_with_and_without_shadows(const RenderContext& context,
                                              const SurfaceInteraction& si, const Bsdf& bsdf,
                                              const Vec3& wo, Sampler& sampler, Vec3* unshadowed) {
  constexpr uint8_t kLobes = kLobeDiffuse | kLobeGlossy;
  Vec3 shadowed(0.0f), free(0.0f);
  auto add = [&](const Vec3& contribution, bool visible) {
    if (!is_finite(contribution)) return;
    free += contribution;
    if (visible) shadowed += contribution;
  };
  auto light_term = [&](const LightSample& ls) {
    float pdf_bsdf;
    const Vec3 f_cos = bsdf_towards(bsdf, wo, ls.wi, kLobes, &pdf_bsdf);
    if (!is_black(f_cos)) add(f_cos * ls.weight, unoccluded(context, si, ls));
  };
  const LightSet& lights = *context.lights;
  for (size_t i = 0; i < lights.size(); ++i) {
    LightSample ls;
    if (lights.sample(i, si.p, sampler.get_2d(), &ls)) light_term(ls);
  }
  const EmissiveMeshes* emissive = context.emissive;
  if (emissive && !emissive->empty()) {
    LightSample ls;
    const float u_pick = sampler.get_1d();
    const Vec2 u_point = sampler.get_2d();
    if (emissive->sample(si.p, u_pick, u_point, &ls)) light_term(ls);
  }
  const Vec3& world = context.scene->world.color;
  if (!is_black(world)) {
    BsdfSample bs;
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    if (bsdf.sample(wo, u_lobe, u, kLobes, &bs))
      add(world * bs.weight, unoccluded(context, si, bs.wi, INFINITY));
  }
  *unshadowed = free;
  return shadowed;
}

Vec3 direct_irradiance(const RenderContext& context, const SurfaceInteraction& si,
                       Sampler& sampler) {
  // A Lambertian BSDF of albedo pi has f = 1, so its reflected radiance is the irradiance.
  Bsdf lambert(si.ns, si.ng, true);
  Lobe lobe;
  lobe.type = LobeType::kLambert;
  lobe.weight = Vec3(kPi);
  lambert.add(lobe);
  return direct_radiance(context, si, lambert, si.ns, sampler);
}

}  // namespace photon

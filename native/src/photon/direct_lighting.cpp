#include "photon/direct_lighting.h"

#include "photon/emissive_mesh.h"
#include "photon/sampling.h"

namespace photon {
namespace {

inline float power_heuristic(float f, float g) {
  const float f2 = f * f, g2 = g * g;
  return f2 + g2 > 0.0f ? f2 / (f2 + g2) : 0.0f;
}

bool unoccluded(const RenderContext& context, const SurfaceInteraction& si, const Vec3& wi,
                float distance) {
  Ray shadow;
  shadow.origin = offset_ray_origin(si.p, si.ng, wi);
  shadow.direction = wi;
  shadow.tmax = std::isfinite(distance) ? distance * (1.0f - 1e-4f) : INFINITY;
  return !context.accel->occluded(shadow, kVisibleShadow);
}

}  // namespace

Vec3 direct_irradiance(const RenderContext& context, const SurfaceInteraction& si,
                       Sampler& sampler) {
  Vec3 e(0.0f);
  const LightSet& lights = *context.lights;
  const Frame frame(si.ns);
  for (size_t i = 0; i < lights.size(); ++i) {
    LightSample ls;
    const Vec2 u_light = sampler.get_2d();
    if (lights.sample(i, si.p, u_light, &ls)) {
      const float cos_theta = dot(si.ns, ls.wi);
      if (cos_theta > 0.0f && dot(si.ng, ls.wi) > 0.0f && unoccluded(context, si, ls.wi, ls.distance)) {
        const float w = ls.pdf > 0.0f ? power_heuristic(ls.pdf, cosine_hemisphere_pdf(cos_theta)) : 1.0f;
        e += ls.weight * (cos_theta * w);
      }
    }
    if (!lights.has_area(i)) continue;
    // BSDF sample: E = L cos / (cos / pi) = pi L, weighted against the light sample.
    const Vec3 wi = frame.to_world(sample_cosine_hemisphere(sampler.get_2d()));
    Vec3 le;
    float distance, pdf_light;
    if (dot(si.ng, wi) <= 0.0f || !lights.eval(i, si.p, wi, &le, &distance, &pdf_light)) continue;
    if (!unoccluded(context, si, wi, distance)) continue;
    e += le * (kPi * power_heuristic(cosine_hemisphere_pdf(dot(si.ns, wi)), pdf_light));
  }

  const EmissiveMeshes* emissive = context.emissive;
  if (emissive && !emissive->empty()) {
    LightSample ls;
    const float u_pick = sampler.get_1d();
    const Vec2 u_point = sampler.get_2d();
    if (emissive->sample(si.p, u_pick, u_point, &ls)) {
      const float cos_theta = dot(si.ns, ls.wi);
      if (cos_theta > 0.0f && dot(si.ng, ls.wi) > 0.0f && unoccluded(context, si, ls.wi, ls.distance))
        e += ls.weight * (cos_theta * power_heuristic(ls.pdf, cosine_hemisphere_pdf(cos_theta)));
    }
    const Vec3 wi = frame.to_world(sample_cosine_hemisphere(sampler.get_2d()));
    if (dot(si.ng, wi) > 0.0f) {
      Ray ray;
      ray.origin = offset_ray_origin(si.p, si.ng, wi);
      ray.direction = wi;
      Hit hit;
      if (context.accel->intersect(ray, kVisibleShadow, &hit)) {
        const Material& mat = context.accel->triangle_material(hit.instance, hit.primitive);
        if (!is_black(mat.emission)) {
          const SurfaceInteraction light_si = context.accel->interaction(hit);
          const float pdf_light =
              emissive->pdf(hit.instance, hit.primitive, hit.t, dot(wi, light_si.ng));
          if (pdf_light > 0.0f)
            e += mat.emission *
                 (kPi * power_heuristic(cosine_hemisphere_pdf(dot(si.ns, wi)), pdf_light));
        }
      }
    }
  }

  // A uniform world is a light from every direction: cosine-weighted sampling gives
  // E = pi * L_world * V with one shadow ray (the cosine and pdf cancel).
  const Vec3& world = context.scene->world.color;
  if (!is_black(world)) {
    const Vec3 wi = frame.to_world(sample_cosine_hemisphere(sampler.get_2d()));
    if (dot(si.ng, wi) > 0.0f && unoccluded(context, si, wi, INFINITY)) e += world * kPi;
  }
  return e;
}

}  // namespace photon

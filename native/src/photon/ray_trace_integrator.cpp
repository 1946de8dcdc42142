#include "photon/ray_trace_integrator.h"

#include "photon/optics.h"
#include "photon/sampling.h"

namespace photon {

Vec3 direct_irradiance(const RenderContext& context, const SurfaceInteraction& si,
                       Sampler& sampler) {
  Vec3 e(0.0f);
  const LightSet& lights = *context.lights;
  for (size_t i = 0; i < lights.size(); ++i) {
    LightSample ls;
    const Vec2 u = sampler.get_2d();
    if (!lights.sample(i, si.p, u, &ls)) continue;
    const float cos_theta = dot(si.ns, ls.wi);
    if (cos_theta <= 0.0f || dot(si.ng, ls.wi) <= 0.0f) continue;
    Ray shadow;
    shadow.origin = offset_ray_origin(si.p, si.ng, ls.wi);
    shadow.direction = ls.wi;
    shadow.tmax = std::isfinite(ls.distance) ? ls.distance * (1.0f - 1e-4f) : INFINITY;
    if (context.accel->occluded(shadow, kVisibleShadow)) continue;
    e += ls.weight * cos_theta;
  }
  // A uniform world is a light from every direction: cosine-weighted sampling gives
  // E = pi * L_world * V with one shadow ray (the cosine and pdf cancel).
  const Vec3& world = context.scene->world.color;
  if (!is_black(world)) {
    const Vec3 wi = Frame(si.ns).to_world(sample_cosine_hemisphere(sampler.get_2d()));
    if (dot(si.ng, wi) > 0.0f) {
      Ray shadow;
      shadow.origin = offset_ray_origin(si.p, si.ng, wi);
      shadow.direction = wi;
      if (!context.accel->occluded(shadow, kVisibleShadow)) e += world * kPi;
    }
  }
  return e;
}

RadianceSample RayTraceIntegrator::radiance_from_hit(const RenderContext& context,
                                                     const Ray& camera_ray,
                                                     const CameraHit& first,
                                                     Sampler& sampler) const {
  RadianceSample result;
  Vec3 throughput(1.0f);
  Ray ray = camera_ray;
  uint32_t mask = kVisibleCamera;
  const int max_depth = context.settings->max_depth;

  for (int depth = 0;; ++depth) {
    Hit hit;
    bool found;
    if (depth == 0) {
      found = first.found;
      hit = first.hit;
    } else {
      found = context.accel->intersect(ray, mask, &hit);
    }
    float t_light;
    Vec3 light_radiance;
    if (context.lights->intersect(ray, found ? hit.t : ray.tmax, mask, &t_light,
                                  &light_radiance)) {
      result.radiance += throughput * light_radiance;
      if (depth == 0) result.alpha = 1.0f;
      break;
    }
    if (!found) {
      // The ray left the scene (camera rays too, whatever their clip distance): world and suns.
      if (depth > 0 || !context.settings->transparent_background)
        result.radiance += throughput * context.scene->world.color;
      result.radiance += throughput * context.lights->distant_radiance(ray.direction, mask);
      break;
    }
    if (depth == 0) result.alpha = 1.0f;

    SurfaceInteraction si = context.accel->interaction(hit);
    const Material& mat = *si.mat;
    const Vec3 wo = -ray.direction;
    result.radiance += throughput * mat.emission;  // emission is two-sided, as in Cycles

    // Shade on the side the ray arrived from.
    if (dot(si.ng, wo) < 0.0f && mat.type != MaterialType::kGlass) {
      si.ng = -si.ng;
      si.ns = -si.ns;
    }
    if (mat.type == MaterialType::kDiffuse) {
      if (!is_black(mat.color))
        result.radiance += throughput * mat.color * kInvPi * direct_irradiance(context, si, sampler);
      break;
    }
    if (depth >= max_depth) break;

    Vec3 wi;
    if (mat.type == MaterialType::kMirror) {
      wi = reflect(wo, si.ns);
      if (dot(wi, si.ng) <= 0.0f) wi = reflect(wo, si.ng);  // keep bumped normals above ground
      mask = kVisibleGlossy;
    } else {  // glass: choose reflection or refraction by Fresnel (one path per sample)
      const bool entering = dot(wo, si.ng) > 0.0f;
      const Vec3 n = entering ? si.ns : -si.ns;
      const float ior = std::max(mat.ior, 1e-3f);
      const float eta = entering ? ior : 1.0f / ior;
      const float f = fresnel_dielectric(dot(wo, n), eta);
      Vec3 wt;
      if (sampler.get_1d() < f || !refract(wo, n, eta, &wt)) {
        wi = reflect(wo, n);
        mask = kVisibleGlossy;
      } else {
        wi = wt;
        mask = kVisibleTransmission;
      }
    }
    throughput *= mat.color;
    if (is_black(throughput)) break;
    ray.origin = offset_ray_origin(si.p, si.ng, wi);
    ray.direction = wi;
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
  }
  return result;
}

std::unique_ptr<Integrator> make_integrator(IntegratorType type) {
  switch (type) {
    case IntegratorType::kRayTrace:
      return std::make_unique<RayTraceIntegrator>();
  }
  return std::make_unique<RayTraceIntegrator>();
}

}  // namespace photon

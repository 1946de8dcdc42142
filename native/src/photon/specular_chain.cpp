#include "photon/specular_chain.h"

#include "photon/optics.h"

namespace photon {

DiffuseVertex trace_specular_chain(const RenderContext& context, Ray ray, const CameraHit* first,
                                   uint32_t mask, Sampler& sampler, Vec3* emitted,
                                   float* alpha) {
  DiffuseVertex v;
  const int max_depth = context.settings->max_depth;
  const bool camera = (mask & kVisibleCamera) != 0;
  for (int depth = 0;; ++depth) {
    Hit hit;
    bool found;
    if (depth == 0 && first) {
      found = first->found;
      hit = first->hit;
    } else {
      found = context.accel->intersect(ray, mask, &hit);
    }
    if (emitted) {
      float t_light;
      Vec3 light_radiance;
      if (context.lights->intersect(ray, found ? hit.t : ray.tmax, mask, &t_light,
                                    &light_radiance)) {
        *emitted += v.throughput * light_radiance;
        if (depth == 0 && alpha) *alpha = 1.0f;
        return v;
      }
    }
    if (!found) {
      v.escaped = true;
      // The ray left the scene (camera rays too, whatever their clip distance): world and suns.
      if (emitted) {
        if (!(camera && depth == 0 && context.settings->transparent_background))
          *emitted += v.throughput * context.scene->world.color;
        *emitted += v.throughput * context.lights->distant_radiance(ray.direction, mask);
      }
      return v;
    }
    if (depth == 0 && alpha) *alpha = 1.0f;

    SurfaceInteraction si = context.accel->interaction(hit);
    const Material& mat = *si.mat;
    const Vec3 wo = -ray.direction;
    if (emitted) *emitted += v.throughput * mat.emission;  // two-sided, as in Cycles

    // Shade on the side the ray arrived from.
    if (dot(si.ng, wo) < 0.0f && mat.type != MaterialType::kGlass) {
      si.ng = -si.ng;
      si.ns = -si.ns;
    }
    if (mat.type == MaterialType::kDiffuse) {
      v.found = true;
      v.si = si;
      v.hit = hit;
      v.depth = depth;
      return v;
    }
    if (depth >= max_depth) return v;

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
    v.throughput *= mat.color;
    if (is_black(v.throughput)) return v;
    ray.origin = offset_ray_origin(si.p, si.ng, wi);
    ray.direction = wi;
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
  }
}

}  // namespace photon

#include "photon/integrators/denoising_features.h"

#include <algorithm>
#include <cmath>

#include "photon/base/optics.h"
#include "photon/integrators/camera_path.h"
#include "photon/integrators/path_walker.h"
#include "photon/lights/emitter_set.h"
#include "photon/render/accel.h"
#include "photon/render/material_eval.h"
#include "photon/render/shader_globals.h"

namespace photon {
namespace {

// Cycles' threshold between specular-like and diffuse-like closures: GGX alpha_x * alpha_y
// above 0.075^2 (delta closures, Transparent and refraction at roughness 0 are specular).
constexpr float kSpecularAlphaSquared = 0.075f * 0.075f;

float average(const Vec3& v) {
  return (v.x + v.y + v.z) / 3.0f;
}

bool is_specular_like(const Lobe& lobe) {
  switch (lobe.type) {
    case LobeType::kGgxReflection:
    case LobeType::kGgxRefraction:
    case LobeType::kGgxGlass: {
      const float alpha_y = lobe.anisotropic() ? lobe.alpha_y : lobe.alpha;
      return lobe.alpha * alpha_y <= kSpecularAlphaSquared;
    }
    case LobeType::kTransparent:
      return true;
    default:  // Lambert, Burley, Oren-Nayar, sheen, velvet, translucent
      return false;
  }
}

// A closure's albedo as Cycles counts it: its weight, times its Fresnel at the view
// direction for a microfacet closure with a Fresnel term (Cycles' fresnel_color; Principled's
// specular, metal and glass), times Schlick's factor at the view for Principled sheen (its
// avg_value). A Glass BSDF without one is Cycles' two closures weighted by F and 1 - F.
Vec3 closure_albedo(const Bsdf& bsdf, const Lobe& lobe, const Vec3& wo) {
  const Vec3 n = length_squared(lobe.normal) > 0.0f ? lobe.normal : bsdf.frame().n;
  const float cos_o = std::clamp(dot(wo, n), 0.0f, 1.0f);
  const float eta = bsdf.front_facing() ? lobe.ior : 1.0f / lobe.ior;
  if ((lobe.type == LobeType::kGgxReflection || lobe.type == LobeType::kGgxGlass) &&
      lobe.fresnel != FresnelMode::kNone)
    return lobe.weight * lobe_reflection_fresnel(lobe, cos_o, eta);
  if (lobe.type == LobeType::kSheen) {
    const float m = 1.0f - cos_o;
    return lobe.weight * (m * m * m * m * m * cos_o);
  }
  return lobe.weight;
}

// World direction into Cycles' camera space: +X right, +Y up, +Z forward (Blender's camera
// looks down its -Z; Cycles flips it). The camera's axes are normalised so a scaled camera
// object does not scale normals.
Vec3 to_camera_space(const Camera& camera, const Vec3& d) {
  const auto& m = camera.camera_to_world.m;
  Vec3 axes[3];
  for (int c = 0; c < 3; ++c) {
    const Vec3 axis(m[0][c], m[1][c], m[2][c]);
    const float len = length(axis);
    axes[c] = len > 0.0f ? axis / len : axis;
  }
  return Vec3(dot(d, axes[0]), dot(d, axes[1]), -dot(d, axes[2]));
}

// Lamps the segment of `ray` up to `t_end` passes through (camera-visible lamps do not stop
// Cycles' rays), summed. `ray.tmin` moves past the last one, as Cycles moves its ray's.
Vec3 lamps_on_segment(const RenderContext& context, Ray* ray, float t_end, uint32_t visibility) {
  Vec3 sum(0.0f);
  float t_lamp;
  Vec3 radiance;
  for (int k = 0; k < 16 && context.emitters &&
                  context.emitters->intersect_lamps(*ray, t_end, visibility, &t_lamp, &radiance);
       ++k) {
    sum += radiance;
    ray->tmin = std::nextafter(t_lamp, INFINITY);
  }
  return sum;
}

Vec3 finite_or_zero(const Vec3& v) {
  return is_finite(v) ? v : Vec3(0.0f);
}

}  // namespace

DenoisingFeatures trace_denoising_features(const RenderContext& context, const Ray& camera_ray,
                                           const CameraHit& first, Sampler& sampler) {
  DenoisingFeatures out;
  Ray ray = camera_ray;
  Hit hit = first.hit;
  bool found = first.found;
  Vec3 throughput(1.0f);       // the feature path's: specular albedos on the way
  Vec3 path_throughput(1.0f);  // the path's own (BSDF weight over pdf), for light met
  float path_length = 0.0f;
  uint32_t visibility = kVisibleCamera;  // of the ray, as the image's path would have it
  uint32_t ray_flags = kRayCamera;       // the Light Path node's view of the ray
  bool see_through = true;               // no bounce but Transparent ones yet
  const int max_hits = std::max(context.settings->max_depth, 0) + 1;
  for (int n = 0; n < max_hits; ++n) {
    // Light the path meets before the features are written adds to the albedo (Cycles'
    // film_write_emission_or_background_pass): lamps, the world, the surface's emission.
    const Vec3 lamps = lamps_on_segment(context, &ray, found ? hit.t : ray.tmax, visibility);
    out.albedo += throughput * path_throughput * lamps;
    if (!found) {
      // A transparent film shows camera rays no world (Cycles evaluates none for them).
      if (!(see_through && context.settings->transparent_background))
        out.albedo += throughput * path_throughput * world_seen_by(context, ray, visibility);
      if (context.lights)
        out.albedo += throughput * path_throughput *
                      context.lights->distant_radiance(ray.direction, visibility);
      break;
    }
    const SurfaceInteraction si = context.accel->interaction(hit);
    const float segment = hit.t - ray.tmin;
    if (std::isfinite(segment)) out.depth += average(throughput) * segment;
    path_length += hit.t;
    ShadeRay shade_ray;
    shade_ray.flags = ray_flags;
    shade_ray.length = path_length;
    const Vec3 wo = normalize(-ray.direction);
    const ShadingPoint shading = shade_surface(si, wo, *context.accel, context.textures, shade_ray);
    const Bsdf& bsdf = shading.bsdf;
    out.albedo += throughput * path_throughput * shading.emission;

    Vec3 normal(0.0f), diffuse_albedo(0.0f), specular_albedo(0.0f);
    float sum_weight = 0.0f, diffuse_weight = 0.0f;
    for (int i = 0; i < bsdf.lobe_count(); ++i) {
      const Lobe& lobe = bsdf.lobe(i);
      const Vec3 albedo = closure_albedo(bsdf, lobe, wo);
      // Cycles' sample weight: the closure's mean weight, its Fresnel included.
      const float weight = std::fabs(average(albedo));
      const Vec3 lobe_n = length_squared(lobe.normal) > 0.0f ? lobe.normal : bsdf.frame().n;
      normal += lobe_n * weight;
      sum_weight += weight;
      if (is_specular_like(lobe)) {
        specular_albedo += albedo;
      } else {
        diffuse_albedo += albedo;
        diffuse_weight += weight;
      }
    }
    // Written here unless 75% or more of the weight is specular-like (then the next bounce).
    if (sum_weight == 0.0f || diffuse_weight * 4.0f > sum_weight) {
      if (sum_weight != 0.0f) normal = normal / sum_weight;
      out.normal = finite_or_zero(to_camera_space(context.scene->camera, normal));
      out.albedo += throughput * diffuse_albedo;
      break;
    }
    throughput = throughput * specular_albedo;
    // On along the sample's bounce, whichever closure it picks (as the path Cycles follows).
    BsdfSample bs;
    const float u_lobe = sampler.get_1d();
    if (!bsdf.sample(wo, u_lobe, sampler.get_2d(), kLobeAll, &bs) || !(bs.pdf > 0.0f)) break;
    path_throughput = path_throughput * bs.weight;
    if (!bs.transparent) {
      see_through = false;
      visibility = visibility_after(bs.flags);
      ray_flags = ((bs.flags & kLobeTransmission) ? kRayTransmit : kRayReflect) |
                  ((bs.flags & kLobeDiffuse) ? kRayDiffuse : kRayGlossy) |
                  (bs.is_delta() ? kRaySingular : 0u);
    }
    spawn_ray(si, bs.wi, context.accel->length_scale(), &ray);
    found = context.accel->intersect(ray, visibility, &hit);
  }
  if (!std::isfinite(out.depth)) out.depth = 0.0f;
  out.albedo = finite_or_zero(out.albedo);
  return out;
}

}  // namespace photon

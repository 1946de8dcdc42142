#include "photon/integrators/camera_path.h"

#include "photon/lights/direct_lighting.h"
#include "photon/render/matte.h"

namespace photon {
namespace {

constexpr int kRouletteDepth = 3;  // Russian roulette on the throughput after this many bounces

// Lamp surfaces, the world and suns that a segment reaches, if it counts emission.
bool add_escaped_or_lamp(const RenderContext& context, const Ray& ray, bool found, float t_hit,
                         uint32_t mask, const Vec3& throughput, bool count_emission,
                         bool camera_primary, Vec3* direct) {
  float t_light;
  Vec3 lamp;
  if (context.lights->intersect(ray, found ? t_hit : ray.tmax, mask, &t_light, &lamp)) {
    if (count_emission) *direct += throughput * lamp;
    return true;
  }
  if (!found && count_emission) {
    // The ray left the scene (camera rays too, whatever their clip distance): world and suns.
    if (!(camera_primary && context.settings->transparent_background))
      *direct += throughput * context.scene->world.color;
    *direct += throughput * context.lights->distant_radiance(ray.direction, mask);
  }
  return false;
}

}  // namespace

uint32_t visibility_after(uint8_t flags) {
  if (flags & kLobeTransmission) return kVisibleTransmission;
  if (flags & kLobeDiffuse) return kVisibleDiffuse;
  return kVisibleGlossy;
}

void trace_camera_path(const RenderContext& context, const Ray& camera_ray, const CameraHit& first,
                       Sampler& sampler, const DiffuseShader& shade_diffuse, RadianceSample* result,
                       uint8_t light_sampled) {
  const int max_depth = context.settings->max_depth;
  Ray ray = camera_ray;
  uint32_t mask = kVisibleCamera;
  Vec3 throughput(1.0f);
  bool count_emission = true;  // false after a rough lobe: light sampling counted that light
  bool after_glossy = false;
  bool see_through = true;  // only Transparent BSDFs so far (for alpha)
  for (int depth = 0;; ++depth) {
    Hit hit;
    const bool found = depth == 0 ? first.found : context.accel->intersect(ray, mask, &hit);
    if (depth == 0 && found) hit = first.hit;
    const bool primary = see_through && mask == kVisibleCamera;
    if (add_escaped_or_lamp(context, ray, found, hit.t, mask, throughput, count_emission, primary,
                            &result->direct)) {
      if (depth == 0) result->alpha = 1.0f;
      return;
    }
    if (!found) {
      // Alpha: what the camera sees of the background through transparent surfaces.
      if (primary && depth > 0)
        result->alpha =
            std::clamp(1.0f - (throughput.x + throughput.y + throughput.z) / 3.0f, 0.0f, 1.0f);
      return;
    }
    if (depth == 0) result->alpha = 1.0f;

    const SurfaceInteraction si = context.accel->interaction(hit);
    const Vec3 wo = -ray.direction;
    // Holdouts and shadow catchers are mattes to camera rays only (matte.h).
    const Matte matte = primary ? matte_at(context, hit) : Matte::kNone;
    if (matte == Matte::kShadowCatcher) {
      // A see-through filter of the shadow ratio: whatever lies behind (the world, or
      // transparency with Film > Transparent) shows darkened by the shadows cast here.
      throughput *= shadow_catcher_ratio(context, si, wo, sampler);
      if (is_black(throughput) || depth >= max_depth) return;
      ray.origin = offset_ray_origin(si.p, si.ng, ray.direction, context.accel->length_scale());
      ray.tmin = 0.0f;
      ray.tmax = INFINITY;
      continue;
    }
    ShadingPoint sp = shade(context, si, wo);
    if (primary && (matte == Matte::kHoldout || sp.holdout > 0.0f)) {
      // Cycles' integrate_surface_holdout: the held-out share of the throughput leaves the
      // pixel's colour and alpha; a surface held out entirely ends the path.
      const Vec3 held = matte == Matte::kHoldout ? hold_out_object(&sp) : Vec3(sp.holdout);
      result->holdout +=
          (throughput.x * held.x + throughput.y * held.y + throughput.z * held.z) / 3.0f;
      if (held.x >= 1.0f && held.y >= 1.0f && held.z >= 1.0f) return;
    }
    if (count_emission) result->direct += throughput * sp.emission;
    const Bsdf& bsdf = sp.bsdf;
    if (bsdf.empty()) return;

    const PathVertex vertex{&si, &sp, wo, throughput, depth, after_glossy};
    if (bsdf.flags() & light_sampled)
      result->direct += throughput * direct_radiance(context, si, bsdf, wo, sampler, light_sampled);
    if (bsdf.flags() & kLobeDiffuse) shade_diffuse(vertex, result);

    // Continue through the lobes that are ray traced: specular and glossy.
    if (depth >= max_depth) return;
    const uint8_t traced = kLobeGlossy | kLobeSpecular;
    if (!(bsdf.flags() & traced)) return;
    const float u_lobe = sampler.get_1d();
    const Vec2 u = sampler.get_2d();
    BsdfSample s;
    if (!bsdf.sample(wo, u_lobe, u, traced, &s) || is_black(s.weight)) return;
    throughput *= s.weight;
    if (depth + 1 >= kRouletteDepth) {
      const float q = std::min(1.0f, max_component(throughput));
      if (!(sampler.get_1d() < q)) return;
      throughput = throughput / q;
    }
    const bool transparent =
        s.is_delta() && !(s.flags & kLobeReflection) && dot(s.wi, ray.direction) > 0.9999f;
    see_through = see_through && transparent;
    count_emission = s.is_delta();
    after_glossy = after_glossy || !s.is_delta();
    if (!transparent) mask = visibility_after(s.flags);  // through Transparent: same ray type
    ray.origin = offset_ray_origin(si.p, si.ng, s.wi, context.accel->length_scale());
    ray.direction = s.wi;
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
  }
}

}  // namespace photon

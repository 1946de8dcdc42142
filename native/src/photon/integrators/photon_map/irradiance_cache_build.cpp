#include "photon/integrators/photon_map/irradiance_cache_build.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>

#include "photon/scene/camera.h"
#include "photon/integrators/camera_path.h"
#include "photon/render/matte.h"

namespace photon {
namespace {

constexpr uint64_t kCacheStreamTag = 0x1CAC4E5EEDull;  // separates record samplers from pixels

// World size of one pixel at distance `path_length` along a camera path: the spacing of the
// ray origins plus the angle between neighbouring rays (perspective and orthographic alike).
struct Footprint {
  float origin = 0.0f, angle = 0.0f;
  float at(float path_length) const { return origin + angle * path_length; }
};

Footprint pixel_footprint(const Camera& camera, float fx, float fy, float dx, float dy) {
  const Vec2 centre(0.5f, 0.5f);
  const Ray r = generate_camera_ray(camera, fx, fy, centre);
  const Ray rx = generate_camera_ray(camera, fx + dx, fy, centre);
  const Ray ry = generate_camera_ray(camera, fx, fy + dy, centre);
  Footprint f;
  f.origin = 0.5f * (length(rx.origin - r.origin) + length(ry.origin - r.origin));
  f.angle = 0.5f * (length(rx.direction - r.direction) + length(ry.direction - r.direction));
  return f;
}

// The records one candidate pixel adds: at every diffuse point along its camera path through
// delta lobes that `previous` does not cover.
void records_at_pixel(const RenderContext& context, const IrradianceCacheSettings& settings,
                      const RecordGather& gather, const IrradianceCache& previous, int level,
                      int px, int py, std::vector<IrradianceRecord>* out, uint64_t* candidates) {
  const RenderSettings& s = *context.settings;
  const Camera& camera = context.scene->camera;
  const float inv_w = 1.0f / s.full_width, inv_h = 1.0f / s.full_height;
  const float fx = (px + 0.5f) * inv_w, fy = (py + 0.5f) * inv_h;
  const Footprint footprint = pixel_footprint(camera, fx, fy, inv_w, inv_h);
  const uint64_t pixel = static_cast<uint64_t>(py) * s.full_width + px;
  // Chooses between delta lobes (glass reflects or refracts) along the path.
  Sampler path_sampler(s.seed, hash_combine(kCacheStreamTag, pixel * 8 + level), 0);

  Ray ray = generate_camera_ray(camera, fx, fy, Vec2(0.5f, 0.5f));
  uint32_t mask = kVisibleCamera;
  float path_length = 0.0f;
  for (int depth = 0; depth <= s.max_depth; ++depth) {
    Hit hit;
    if (!context.accel->intersect(ray, mask, &hit)) return;
    float t_light;
    Vec3 lamp;
    if (context.lights->intersect(ray, hit.t, mask, &t_light, &lamp)) return;
    path_length += hit.t;
    const SurfaceInteraction si = context.accel->interaction(hit);
    const Vec3 wo = -ray.direction;
    // Mattes as the camera path sees them (matte.h): the render gathers behind a shadow
    // catcher, and nothing at a held-out surface but what its transparency lets through.
    const Matte matte = mask == kVisibleCamera ? matte_at(context, hit) : Matte::kNone;
    if (matte == Matte::kShadowCatcher) {
      ray.origin = offset_ray_origin(si.p, si.ng, ray.direction, context.accel->length_scale());
      ray.tmin = 0.0f;
      ray.tmax = INFINITY;
      continue;
    }
    ShadingPoint sp = shade(context, si, wo);
    if (matte == Matte::kHoldout) hold_out_object(&sp);
    const Bsdf& bsdf = sp.bsdf;
    if (bsdf.empty()) return;
    if ((bsdf.flags() & kLobeDiffuse) && !is_black(bsdf.diffuse_reflectance())) {
      ++*candidates;
      const Vec3 n = bsdf.frame().n;
      if (!previous.covers(si.p, n, settings.coverage * previous.accuracy())) {
        Sampler sampler(s.seed, hash_combine(kCacheStreamTag + 1 + depth, pixel * 8 + level), 0);
        float harmonic = INFINITY;
        const Vec3 value = gather(si, bsdf, settings.rays, sampler, &harmonic);
        const float pixel_size = footprint.at(path_length);
        const float a = previous.accuracy();
        IrradianceRecord r;
        r.p = si.p;
        r.n = n;
        r.value = value;
        r.radius = std::clamp(harmonic, settings.min_pixels * pixel_size / a,
                              settings.max_pixels * pixel_size / a);
        if (std::isfinite(r.radius) && r.radius > 0.0f && is_finite(value)) out->push_back(r);
      }
    }
    if (!(bsdf.flags() & kLobeSpecular)) return;
    BsdfSample bs;
    const float u_lobe = path_sampler.get_1d();
    const Vec2 u = path_sampler.get_2d();
    if (!bsdf.sample(wo, u_lobe, u, kLobeSpecular, &bs) || is_black(bs.weight)) return;
    const bool transparent = !(bs.flags & kLobeReflection) && dot(bs.wi, ray.direction) > 0.9999f;
    if (!transparent) mask = visibility_after(bs.flags);
    ray.origin = offset_ray_origin(si.p, si.ng, bs.wi, context.accel->length_scale());
    ray.direction = bs.wi;
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
  }
}

}  // namespace

IrradianceCache build_irradiance_cache(const RenderContext& context,
                                       const IrradianceCacheSettings& settings,
                                       const RecordGather& gather, const PrepareControl& control,
                                       IrradianceCacheBuildStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const RenderSettings& s = *context.settings;
  const float a = settings.accuracy;
  IrradianceCache cache({}, a);
  std::vector<IrradianceRecord> all;
  if (s.full_width <= 0 || s.full_height <= 0 || settings.rays <= 0) return cache;
  const int finest = std::max(settings.finest_spacing, 1);
  int levels = 0;
  for (int spacing = std::max(settings.coarsest_spacing, finest); spacing >= finest; spacing /= 2)
    ++levels;
  int level = 0;
  std::atomic<uint64_t> candidates{0};
  control.report("Irradiance cache: 0 records", 0.0f);
  for (int spacing = std::max(settings.coarsest_spacing, finest); spacing >= finest;
       spacing /= 2, ++level) {
    const int nx = (s.full_width + spacing - 1) / spacing;
    const int ny = (s.full_height + spacing - 1) / spacing;
    std::vector<std::vector<IrradianceRecord>> found(static_cast<size_t>(nx) * ny);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, found.size(), 8), [&](const auto& range) {
      uint64_t tested = 0;
      // The partitioner hands out ranges far larger than the grain: poll per pixel.
      for (size_t i = range.begin(); i != range.end(); ++i) {
        if (control.cancelled()) break;
        const int px = std::min(static_cast<int>(i % nx) * spacing + spacing / 2, s.full_width - 1);
        const int py =
            std::min(static_cast<int>(i / nx) * spacing + spacing / 2, s.full_height - 1);
        records_at_pixel(context, settings, gather, cache, level, px, py, &found[i], &tested);
      }
      candidates += tested;
    });
    if (control.cancelled()) return IrradianceCache({}, a);
    for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
    cache = IrradianceCache(all, a);
    control.report("Irradiance cache: " + std::to_string(cache.size()) + " records",
                   static_cast<float>(level + 1) / levels);
  }
  if (stats) {
    stats->candidates = candidates.load();
    stats->gather_rays = static_cast<uint64_t>(cache.size()) * settings.rays;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return cache;
}

}  // namespace photon

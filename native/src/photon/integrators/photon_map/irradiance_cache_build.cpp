#include "photon/integrators/photon_map/irradiance_cache_build.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/matte.h"
#include "photon/scene/camera.h"

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

// The records one candidate pixel adds: at every candidate point of its camera path that
// `previous` does not cover.
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

  const Ray ray = generate_camera_ray(camera, fx, fy, Vec2(0.5f, 0.5f));
  visit_cache_candidates(context, ray, path_sampler, [&](const PathVertex& v) {
    const SurfaceInteraction& si = *v.si;
    const Bsdf& bsdf = v.shading->bsdf;
    ++*candidates;
    const Vec3 n = bsdf.frame().n;
    if (previous.covers(si.p, n, settings.coverage * previous.accuracy())) return;
    Sampler sampler(s.seed, hash_combine(kCacheStreamTag + 1 + v.depth, pixel * 8 + level), 0);
    float harmonic = INFINITY;
    const Vec3 value = gather(si, bsdf, settings.rays, sampler, &harmonic);
    const float pixel_size = footprint.at(v.path_length);
    const float a = previous.accuracy();
    IrradianceRecord r;
    r.p = si.p;
    r.n = n;
    r.value = value;
    r.radius = std::clamp(harmonic, settings.min_pixels * pixel_size / a,
                          settings.max_pixels * pixel_size / a);
    if (std::isfinite(r.radius) && r.radius > 0.0f && is_finite(value)) out->push_back(r);
  });
}

}  // namespace

void visit_cache_candidates(const RenderContext& context, const Ray& camera_ray,
                            Sampler& path_sampler,
                            const std::function<void(const PathVertex&)>& candidate) {
  RadianceSample unused;
  walk_camera_path(
      context, camera_ray, nullptr, path_sampler, cache_placement_walk(context),
      [&](const PathVertex& v, RadianceSample*) {
        if (!is_black(v.shading->bsdf.diffuse_reflectance())) candidate(v);
      },
      &unused);
}

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

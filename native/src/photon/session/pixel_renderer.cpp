#include "photon/session/pixel_renderer.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <memory>
#include <vector>

#include "photon/scene/camera.h"
#include "photon/scene/pixel_filter.h"
#include "photon/session/data_passes.h"

namespace photon {

float finite_average(float sum, float inv_spp) {
  const float v = sum * inv_spp;
  return std::isnan(v) ? 0.0f : std::clamp(v, -FLT_MAX, FLT_MAX);
}

Ray camera_sample_ray(const PixelFilter& filter, const Camera& camera, int full_width,
                      int full_height, int px, int py, Sampler& sampler) {
  const Vec2 jitter = filter.sample(sampler.get_2d());
  const Vec2 lens = sampler.get_2d();
  // Times the reciprocal, not divided: the reference images depend on these exact bits.
  const float inv_w = 1.0f / full_width, inv_h = 1.0f / full_height;
  return generate_camera_ray(camera, (px + jitter.x) * inv_w, (py + jitter.y) * inv_h, lens);
}

namespace {

// Sample k of the pixels [x, x + n) of row py: each pixel's sampler (its stream depends on the
// pixel's place in the full frame only), its camera ray, traced with the row's others as one
// coherent Embree stream, and the first hit.
void trace_camera_row(const RenderContext& context, const PixelFilter& filter, int x, int py, int k,
                      size_t n, Sampler* samplers, Ray* rays, Hit* hits, bool* found) {
  const RenderSettings& s = *context.settings;
  for (size_t i = 0; i < n; ++i) {
    const int px = x + static_cast<int>(i);
    const uint64_t pixel_index = static_cast<uint64_t>(py) * s.full_width + px;
    samplers[i] =
        Sampler(s.seed, pixel_index, static_cast<uint32_t>(k), static_cast<uint32_t>(s.samples));
    rays[i] = camera_sample_ray(filter, context.scene->camera, s.full_width, s.full_height, px, py,
                                samplers[i]);
  }
  context.accel->intersect_coherent(rays, n, kVisibleCamera, hits, found);
}

}  // namespace

bool render_data_passes(const RenderContext& context, int x, int y, int width, int height,
                        float* data, const std::atomic<bool>& cancel) {
  const RenderSettings& s = *context.settings;
  const PixelFilter filter(s.filter_type, s.filter_width);
  const size_t n = static_cast<size_t>(width);
  const size_t row_floats = n * data_pass_pixel_floats(s.data_passes);
  std::vector<Sampler> samplers(n, Sampler(0, 0, 0));
  std::vector<Ray> rays(n);
  std::vector<Hit> hits(n);
  std::unique_ptr<bool[]> found(new bool[n]);
  DataPassRow data_row(context, s.data_passes, n);
  for (int row = 0; row < height; ++row) {
    const int py = y + row;
    data_row.clear();
    for (int k = 0; k < s.samples; ++k) {
      if (cancel.load(std::memory_order_relaxed)) return false;
      trace_camera_row(context, filter, x, py, k, n, samplers.data(), rays.data(), hits.data(),
                       found.get());
      for (size_t i = 0; i < n; ++i) {
        CameraHit first;
        first.found = found[i];
        if (first.found) first.hit = hits[i];
        data_row.add(i, k, static_cast<uint64_t>(py) * s.full_width + x + i, rays[i], first);
      }
    }
    data_row.finish(s.samples, data + static_cast<size_t>(row) * row_floats);
  }
  return true;
}

bool render_pixels(const RenderContext& context, const Integrator& integrator, int x, int y,
                   int width, int height, float* rgba, const std::atomic<bool>& cancel,
                   uint64_t* non_finite, float* passes, float* data, int* rows_done) {
  const RenderSettings& s = *context.settings;
  const float inv_spp = 1.0f / s.samples;
  const PixelFilter filter(s.filter_type, s.filter_width);
  const float colour_scale = inv_spp * s.exposure;  // the film's exposure scales colour only
  const size_t n = static_cast<size_t>(width);

  std::vector<Sampler> samplers(n, Sampler(0, 0, 0));
  std::vector<Ray> rays(n);
  std::vector<Hit> hits(n);
  std::unique_ptr<bool[]> found(new bool[n]);
  std::vector<Vec3> sums(n);
  std::vector<Vec3> pass_sums(passes ? n * kPassCount : 0);
  std::vector<float> alphas(n);
  std::unique_ptr<DataPassRow> data_row;
  if (data) data_row = std::make_unique<DataPassRow>(context, s.data_passes, n);
  if (rows_done) *rows_done = 0;

  for (int row = 0; row < height; ++row) {
    const int py = y + row;
    std::fill(sums.begin(), sums.end(), Vec3(0.0f));
    std::fill(alphas.begin(), alphas.end(), 0.0f);
    std::fill(pass_sums.begin(), pass_sums.end(), Vec3(0.0f));
    if (data_row) data_row->clear();
    for (int k = 0; k < s.samples; ++k) {
      if (cancel.load(std::memory_order_relaxed)) return false;
      trace_camera_row(context, filter, x, py, k, n, samplers.data(), rays.data(), hits.data(),
                       found.get());
      for (size_t i = 0; i < n; ++i) {
        CameraHit first;
        first.found = found[i];
        if (first.found) first.hit = hits[i];
        if (data_row)
          data_row->add(i, k, static_cast<uint64_t>(py) * s.full_width + x + i, rays[i], first);
        const RadianceSample r = integrator.radiance_from_hit(context, rays[i], first, samplers[i]);
        const Vec3 radiance = r.radiance();
        if (!is_finite(radiance) || !is_finite(r.photon_map)) {
          ++*non_finite;
          continue;
        }
        sums[i] += radiance;
        // Without Film > Transparent the background is opaque too, as in Blender's engines;
        // holdouts make the pixel transparent either way (Cycles).
        const float coverage = s.transparent_background ? r.alpha : 1.0f;
        alphas[i] += r.holdout > 0.0f ? std::max(coverage - r.holdout, 0.0f) : coverage;
        if (passes) {
          Vec3* p = &pass_sums[i * kPassCount];
          p[0] += r.direct;
          p[1] += r.indirect;
          p[2] += r.caustic;
          p[3] += r.photon_map;
        }
      }
    }
    float* out = rgba + static_cast<size_t>(row) * n * 4;
    for (size_t i = 0; i < n; ++i) {
      out[4 * i + 0] = finite_average(sums[i].x, colour_scale);
      out[4 * i + 1] = finite_average(sums[i].y, colour_scale);
      out[4 * i + 2] = finite_average(sums[i].z, colour_scale);
      out[4 * i + 3] = alphas[i] * inv_spp;
    }
    if (passes) {
      float* pout = passes + static_cast<size_t>(row) * n * kPassFloats;
      for (size_t i = 0; i < n * kPassCount; ++i) {
        pout[3 * i + 0] = finite_average(pass_sums[i].x, colour_scale);
        pout[3 * i + 1] = finite_average(pass_sums[i].y, colour_scale);
        pout[3 * i + 2] = finite_average(pass_sums[i].z, colour_scale);
      }
    }
    if (data_row)
      data_row->finish(s.samples,
                       data + static_cast<size_t>(row) * n * data_pass_pixel_floats(s.data_passes));
    if (rows_done) *rows_done = row + 1;
  }
  return true;
}

}  // namespace photon

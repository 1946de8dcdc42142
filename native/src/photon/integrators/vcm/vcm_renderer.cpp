#include "photon/integrators/vcm/vcm_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/integrators/spectral_path.h"
#include "photon/integrators/vcm/vcm_camera_paths.h"
#include "photon/integrators/vcm/vcm_grid.h"
#include "photon/integrators/vcm/vcm_light_paths.h"
#include "photon/scene/camera.h"
#include "photon/session/pixel_renderer.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;
constexpr uint64_t kCameraStream = 0x56434D43414D;      // "VCMCAM"
constexpr uint64_t kWavelengthStream = 0x56434D57564C;  // "VCMWVL"
// Russian roulette ends paths long before this; it bounds chains between perfect mirrors.
constexpr int kMaxPathLength = 64;
// Automatic initial radius, in pixel footprints at the median depth the camera sees.
constexpr float kAutoRadiusPixels = 2.0f;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

bool VcmRenderer::supports_camera(const RenderContext& context) {
  return VcmCamera(context.scene->camera, *context.settings).supported();
}

VcmRenderer::VcmRenderer(const RenderContext& context, std::vector<std::string>* warnings)
    : context_(context),
      width_(context.settings->x1 - context.settings->x0),
      height_(context.settings->y1 - context.settings->y0),
      camera_(context.scene->camera, *context.settings),
      sum_(static_cast<size_t>(width_) * height_, Vec3(0.0f)),
      alpha_(static_cast<size_t>(width_) * height_, 0.0f) {
  const PhotonSources sources(context);
  PhotonFrame frame;
  frame.center = sources.scene_center();
  frame.radius = sources.scene_radius();
  lights_ = std::make_unique<VcmLights>(context, frame, warnings);
  const RenderSettings& s = *context.settings;
  const float floor_radius = 1e-6f * context.accel->length_scale();
  initial_radius_ = s.sppm_initial_radius > 0.0f
                        ? std::min(s.sppm_initial_radius, 2.0f * frame.radius)
                        : automatic_radius();
  if (!(initial_radius_ > floor_radius))
    initial_radius_ = std::max(floor_radius, 0.01f * frame.radius);
}

VcmRenderer::~VcmRenderer() = default;

float VcmRenderer::automatic_radius() const {
  // The distance between neighbouring pixels' centre rays at the depth each sees, on a grid of
  // at most 64 x 64 pixels of the whole frame (not the render region: a band of a frame must
  // render with the full frame's radius); the median.
  const RenderSettings& s = *context_.settings;
  const Camera& camera = context_.scene->camera;
  const float inv_w = 1.0f / s.full_width, inv_h = 1.0f / s.full_height;
  const int step = std::max(1, std::max(s.full_width, s.full_height) / 64);
  std::vector<float> seen;
  for (int py = 0; py < s.full_height; py += step)
    for (int px = 0; px < s.full_width; px += step) {
      const Vec2 lens(0.5f, 0.5f);
      const Ray a = generate_camera_ray(camera, (px + 0.5f) * inv_w, (py + 0.5f) * inv_h, lens);
      const Ray b = generate_camera_ray(camera, (px + 1.5f) * inv_w, (py + 0.5f) * inv_h, lens);
      Hit hit;
      if (!context_.accel->intersect(a, kVisibleCamera, &hit)) continue;
      const float r = kAutoRadiusPixels *
                      length((b.origin + hit.t * b.direction) - (a.origin + hit.t * a.direction));
      if (std::isfinite(r) && r > 0.0f) seen.push_back(r);
    }
  if (seen.empty()) return 0.0f;
  std::nth_element(seen.begin(), seen.begin() + seen.size() / 2, seen.end());
  return seen[seen.size() / 2];
}

float VcmRenderer::radius(int iteration) const {
  const float alpha = context_.settings->sppm_alpha;
  return initial_radius_ * std::pow(static_cast<float>(iteration + 1), 0.5f * (alpha - 1.0f));
}

bool VcmRenderer::iterate(const std::atomic<bool>& cancel) {
  const RenderSettings& s = *context_.settings;
  const auto iteration = static_cast<uint32_t>(stats_.iterations);
  const VcmMis mis =
      VcmMis::make(s.vcm_mode, radius(stats_.iterations),
                   std::max<uint64_t>(s.sppm_photons_per_iteration, 1), kMaxPathLength);
  // Spectral mode: one set of wavelengths for the iteration's light and camera subpaths, so
  // connections and merges join them at the same wavelengths; stratified over the iterations.
  SampledWavelengths wavelengths;
  VcmColours colours;
  if (spectral_mode(context_)) {
    wavelengths = sample_wavelengths(
        s, Sampler(s.seed, kWavelengthStream, iteration, static_cast<uint32_t>(s.sppm_iterations)));
    colours.wl = &wavelengths;
  }
  auto t0 = Clock::now();
  const VcmLightPass pass =
      trace_vcm_light_paths(context_, *lights_, camera_, mis, iteration, cancel, colours);
  if (pass.cancelled) return false;
  stats_.rays += pass.rays;
  stats_.photons_recorded = pass.vertices.size();
  std::vector<Vec3> light_image(sum_.size(), Vec3(0.0f));
  apply_vcm_splats(pass.splats, camera_, s, &light_image);
  const VcmGrid grid = mis.use_vm ? VcmGrid(pass.vertices, mis.radius) : VcmGrid();
  stats_.peak_photon_bytes =
      std::max(stats_.peak_photon_bytes, pass.vertices.size() * (sizeof(VcmLightVertex) + 8));
  stats_.photon_seconds += seconds_since(t0);

  t0 = Clock::now();
  std::atomic<uint64_t> non_finite{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 1), [&](const auto& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int py = s.y0 + row;
      for (int col = 0; col < width_; ++col) {
        const int px = s.x0 + col;
        const size_t i = static_cast<size_t>(row) * width_ + col;
        const uint64_t pixel_index = static_cast<uint64_t>(py) * s.full_width + px;
        Sampler sampler(s.seed, hash_combine(kCameraStream, pixel_index), iteration,
                        static_cast<uint32_t>(s.sppm_iterations));
        const VcmCameraSample c =
            trace_vcm_camera_path(context_, *lights_, camera_, mis, pass,
                                  pixel_index % mis.light_paths, grid, px, py, sampler, colours);
        const Vec3 estimate = c.radiance + light_image[i];
        if (!is_finite(estimate)) {
          non_finite.fetch_add(1, std::memory_order_relaxed);
          continue;
        }
        sum_[i] += estimate;
        alpha_[i] += s.transparent_background ? c.alpha : 1.0f;
      }
    }
  });
  stats_.camera_seconds += seconds_since(t0);
  if (cancel.load()) return false;
  stats_.non_finite += non_finite.load();
  stats_.photons_emitted += mis.light_paths;
  ++stats_.iterations;
  return true;
}

void VcmRenderer::write_image(float* rgba, float* passes) const {
  const RenderSettings& s = *context_.settings;
  const float inv_k = 1.0f / static_cast<float>(std::max(stats_.iterations, 1));
  const float scale = inv_k * s.exposure;
  for (size_t i = 0; i < sum_.size(); ++i) {
    rgba[4 * i + 0] = finite_average(sum_[i].x, scale);
    rgba[4 * i + 1] = finite_average(sum_[i].y, scale);
    rgba[4 * i + 2] = finite_average(sum_[i].z, scale);
    rgba[4 * i + 3] = alpha_[i] * inv_k;
    if (passes) std::fill(passes + i * kPassFloats, passes + (i + 1) * kPassFloats, 0.0f);
  }
}

}  // namespace photon

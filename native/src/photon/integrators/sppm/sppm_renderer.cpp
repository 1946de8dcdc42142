#include "photon/integrators/sppm/sppm_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "photon/integrators/photon_map/photon_memory.h"
#include "photon/integrators/spectral_path.h"
#include "photon/integrators/sppm/photon_kdtree.h"
#include "photon/integrators/sppm/sppm_camera.h"
#include "photon/integrators/sppm/sppm_photons.h"
#include "photon/scene/camera.h"
#include "photon/scene/pixel_filter.h"
#include "photon/session/pixel_renderer.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;
constexpr uint64_t kCameraStream = 0x5350504D43414D;      // "SPPMCAM"
constexpr uint64_t kWavelengthStream = 0x5350504D57564C;  // "SPPMWVL"
// Automatic initial radius, in pixel footprints at the pixel's surface: wide enough that the
// first iterations find photons, narrow enough to blur little before R shrinks.
constexpr float kAutoRadiusPixels = 2.0f;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

uint64_t sppm_photons_that_fit(uint64_t requested, double records_per_photon, double budget_bytes) {
  const double per_photon = records_per_photon * kSppmPeakBytesPerRecord;
  if (!(budget_bytes > 0.0) || !(per_photon > 0.0)) return requested;
  const double fit = std::floor(budget_bytes / per_photon);
  return fit >= static_cast<double>(requested) ? requested
                                               : std::max<uint64_t>(1, static_cast<uint64_t>(fit));
}

SppmRenderer::SppmRenderer(const RenderContext& context, std::vector<std::string>* warnings)
    : context_(context),
      sources_(context),
      width_(context.settings->x1 - context.settings->x0),
      height_(context.settings->y1 - context.settings->y0),
      pixels_(static_cast<size_t>(width_) * height_) {
  const uint64_t requested = context.settings->sppm_photons_per_iteration;
  photons_per_iteration_ = requested;
  // The pilot's photons come from an iteration index no render reaches.
  constexpr uint64_t kPilotPhotons = 4096;
  constexpr uint32_t kPilotIteration = 0xFFFFFFFFu;
  const double budget = kSppmMemoryFraction * static_cast<double>(available_memory_bytes());
  // A photon records at most one photon per bounce: below that bound no pilot is needed.
  constexpr double kMaxRecordsPerPhoton = 64.0;
  if (static_cast<double>(requested) * kMaxRecordsPerPhoton * kSppmPeakBytesPerRecord < budget)
    return;
  const std::atomic<bool> no_cancel{false};
  const SppmPhotonPass pilot =
      trace_sppm_photons(context, sources_, kPilotIteration, kPilotPhotons, no_cancel);
  const double records = static_cast<double>(pilot.photons.size()) / kPilotPhotons;
  photons_per_iteration_ = sppm_photons_that_fit(requested, records, budget);
  if (photons_per_iteration_ < requested && warnings)
    warnings->push_back(
        "sppm_photons_per_iteration = " + std::to_string(requested) + " would need about " +
        bytes_text(static_cast<double>(requested) * records * kSppmPeakBytesPerRecord) +
        " for one iteration's photons, more than half of the memory available (" +
        bytes_text(2.0 * budget) + "): " + std::to_string(photons_per_iteration_) +
        " photons per iteration are traced instead");
}

void SppmRenderer::initial_radii(const std::atomic<bool>& cancel) {
  const RenderSettings& s = *context_.settings;
  const float floor_radius = 1e-6f * context_.accel->length_scale();
  if (s.sppm_initial_radius > 0.0f) {
    // A disc wider than the scene gathers no more photons, only reads them all at every pixel.
    const float radius = std::min(s.sppm_initial_radius, 2.0f * sources_.scene_radius());
    for (SppmPixel& p : pixels_) p.radius = std::max(radius, floor_radius);
    return;
  }
  // The distance between the centre rays of a pixel and of its right neighbour, at the depth
  // of the pixel's first hit (0 where the pixel sees nothing).
  const Camera& camera = context_.scene->camera;
  const float inv_w = 1.0f / s.full_width, inv_h = 1.0f / s.full_height;
  const auto centre_radius = [&](int px, int py) {
    const Vec2 lens(0.5f, 0.5f);
    const Ray a = generate_camera_ray(camera, (px + 0.5f) * inv_w, (py + 0.5f) * inv_h, lens);
    const Ray b = generate_camera_ray(camera, (px + 1.5f) * inv_w, (py + 0.5f) * inv_h, lens);
    Hit hit;
    if (!context_.accel->intersect(a, kVisibleCamera, &hit)) return 0.0f;
    const Vec3 d = (b.origin + hit.t * b.direction) - (a.origin + hit.t * a.direction);
    const float r = kAutoRadiusPixels * length(d);
    return std::isfinite(r) ? r : 0.0f;
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 1), [&](const auto& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      if (cancel.load(std::memory_order_relaxed)) return;
      for (int col = 0; col < width_; ++col)
        pixels_[static_cast<size_t>(row) * width_ + col].radius =
            centre_radius(s.x0 + col, s.y0 + row);
    }
  });
  // Pixels that see nothing at their centre take the median radius of the whole frame's pixels
  // that see something, so a render border does not change it (a band of a frame equals the
  // same rows of the full render).
  std::vector<float> seen;
  const bool whole_frame = s.x0 == 0 && s.y0 == 0 && s.x1 == s.full_width && s.y1 == s.full_height;
  if (whole_frame) {
    for (const SppmPixel& p : pixels_)
      if (p.radius > 0.0f) seen.push_back(p.radius);
  } else {
    std::vector<float> frame(static_cast<size_t>(s.full_width) * s.full_height);
    tbb::parallel_for(tbb::blocked_range<int>(0, s.full_height, 1), [&](const auto& rows) {
      for (int py = rows.begin(); py != rows.end(); ++py) {
        if (cancel.load(std::memory_order_relaxed)) return;
        for (int px = 0; px < s.full_width; ++px)
          frame[static_cast<size_t>(py) * s.full_width + px] = centre_radius(px, py);
      }
    });
    for (float r : frame)
      if (r > 0.0f) seen.push_back(r);
  }
  if (cancel.load()) return;
  float fallback = 0.01f * sources_.scene_radius();
  if (!seen.empty()) {
    std::nth_element(seen.begin(), seen.begin() + seen.size() / 2, seen.end());
    fallback = seen[seen.size() / 2];
  }
  for (SppmPixel& p : pixels_)
    p.radius = std::max(p.radius > 0.0f ? p.radius : fallback, floor_radius);
}

bool SppmRenderer::iterate(const std::atomic<bool>& cancel) {
  const RenderSettings& s = *context_.settings;
  if (!radii_set_) {
    initial_radii(cancel);
    if (cancel.load()) return false;
    radii_set_ = true;
  }
  const auto iteration = static_cast<uint32_t>(stats_.iterations);

  // Spectral mode: one set of wavelengths for the iteration's photons and camera paths, so a
  // visible point meets photons at its own wavelengths; stratified over the iterations.
  std::optional<SampledWavelengths> wavelengths;
  if (spectral_mode(context_))
    wavelengths = sample_wavelengths(
        s, Sampler(s.seed, kWavelengthStream, iteration, static_cast<uint32_t>(s.sppm_iterations)));
  const SampledWavelengths* wl = wavelengths ? &*wavelengths : nullptr;

  auto t0 = Clock::now();
  SppmPhotonPass pass =
      trace_sppm_photons(context_, sources_, iteration, photons_per_iteration_, cancel, wl);
  if (pass.cancelled) return false;
  stats_.rays += pass.rays;
  stats_.photons_recorded = pass.photons.size();
  const PhotonKdTree photons(std::move(pass.photons));
  stats_.peak_photon_bytes = std::max(stats_.peak_photon_bytes, photons.memory_bytes());
  stats_.photon_seconds += seconds_since(t0);

  t0 = Clock::now();
  const PixelFilter filter(s.filter_type, s.filter_width);
  const Camera& camera = context_.scene->camera;
  const float alpha = s.sppm_alpha;
  std::atomic<uint64_t> non_finite{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 1), [&](const auto& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      if (cancel.load(std::memory_order_relaxed)) return;
      const int py = s.y0 + row;
      for (int col = 0; col < width_; ++col) {
        const int px = s.x0 + col;
        SppmPixel& pixel = pixels_[static_cast<size_t>(row) * width_ + col];
        const uint64_t pixel_index = static_cast<uint64_t>(py) * s.full_width + px;
        Sampler sampler(s.seed, hash_combine(kCameraStream, pixel_index), iteration,
                        static_cast<uint32_t>(s.sppm_iterations));
        const Ray ray =
            camera_sample_ray(filter, camera, s.full_width, s.full_height, px, py, sampler);
        const SppmCameraSample c =
            trace_sppm_camera(context_, ray, sampler, photons, pixel.radius, wl);
        if (!is_finite(c.direct) || !is_finite(c.phi)) {
          non_finite.fetch_add(1, std::memory_order_relaxed);
          continue;
        }
        pixel.direct += c.direct;
        const float coverage = s.transparent_background ? c.alpha : 1.0f;
        pixel.alpha += c.holdout > 0.0f ? std::max(coverage - c.holdout, 0.0f) : coverage;
        if (c.photons > 0) {
          // Eqs. 6-8: keep alpha of the new photons, shrink the disc to match, and scale the
          // flux gathered so far to the smaller disc.
          const float m = static_cast<float>(c.photons);
          const float n_new = pixel.n + alpha * m;
          const float r_new = pixel.radius * std::sqrt(n_new / (pixel.n + m));
          pixel.tau = (pixel.tau + c.phi) * ((r_new * r_new) / (pixel.radius * pixel.radius));
          pixel.n = n_new;
          pixel.radius = r_new;
        }
      }
    }
  });
  stats_.camera_seconds += seconds_since(t0);
  if (cancel.load()) return false;
  stats_.non_finite += non_finite.load();
  stats_.photons_emitted += photons_per_iteration_;
  ++stats_.iterations;
  return true;
}

void SppmRenderer::write_image(float* rgba, float* passes) const {
  const RenderSettings& s = *context_.settings;
  const int k = std::max(stats_.iterations, 1);
  const float inv_k = 1.0f / static_cast<float>(k);
  const double emitted = std::max<double>(static_cast<double>(stats_.photons_emitted), 1.0);
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const SppmPixel& p = pixels_[i];
    const double area = kPi * static_cast<double>(p.radius) * p.radius;
    const auto photon_part = [&](float tau) { return static_cast<float>(tau / (emitted * area)); };
    const Vec3 indirect =
        area > 0.0 ? Vec3(photon_part(p.tau.x), photon_part(p.tau.y), photon_part(p.tau.z))
                   : Vec3(0.0f);
    // Indirect is already an average over iterations: scaled by k, it goes through the same
    // finite_average as every renderer's pixels.
    const Vec3 sum = p.direct + indirect * static_cast<float>(k);
    const float scale = inv_k * s.exposure;
    rgba[4 * i + 0] = finite_average(sum.x, scale);
    rgba[4 * i + 1] = finite_average(sum.y, scale);
    rgba[4 * i + 2] = finite_average(sum.z, scale);
    rgba[4 * i + 3] = p.alpha * inv_k;
    if (passes) {
      float* out = passes + i * kPassFloats;
      std::fill(out, out + kPassFloats, 0.0f);
      for (int c = 0; c < 3; ++c) {
        out[c] = finite_average(p.direct[c], scale);
        out[3 + c] = finite_average(indirect[c] * static_cast<float>(k), scale);
      }
    }
  }
}

}  // namespace photon

#include "photon/integrators/sppm/sppm_integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "photon/integrators/iterative_frame.h"
#include "photon/integrators/merge_radius.h"
#include "photon/integrators/photon_map/photon_memory.h"
#include "photon/integrators/spectral_path.h"
#include "photon/integrators/sppm/photon_kdtree.h"
#include "photon/integrators/sppm/sppm_camera.h"
#include "photon/integrators/sppm/sppm_photons.h"

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

const std::atomic<bool>& cancel_flag(const RenderControl& control) {
  static const std::atomic<bool> never{false};
  return control.cancel ? *control.cancel : never;
}

}  // namespace

uint64_t sppm_photons_that_fit(uint64_t requested, double records_per_photon, double budget_bytes) {
  return count_that_fits(requested, records_per_photon * kSppmPeakBytesPerRecord, budget_bytes);
}

void SppmIntegrator::prepare(const RenderContext& context, const PrepareControl& control) {
  sources_ = std::make_unique<PhotonSources>(context);
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
      trace_sppm_photons(context, *sources_, kPilotIteration, kPilotPhotons, no_cancel);
  const double records = static_cast<double>(pilot.photons.size()) / kPilotPhotons;
  photons_per_iteration_ = sppm_photons_that_fit(requested, records, budget);
  if (photons_per_iteration_ < requested && control.warn)
    control.warn("sppm_photons_per_iteration = " + std::to_string(requested) +
                 " would need about " +
                 bytes_text(static_cast<double>(requested) * records * kSppmPeakBytesPerRecord) +
                 " for one iteration's photons, more than half of the memory available (" +
                 bytes_text(2.0 * budget) + "): " + std::to_string(photons_per_iteration_) +
                 " photons per iteration are traced instead");
}

void SppmIntegrator::initial_radii(const RenderContext& context, const Film& film,
                                   const RenderControl& control) {
  const RenderSettings& s = *context.settings;
  const std::atomic<bool>& cancel = cancel_flag(control);
  const FilmFrame& f = film.frame();
  const float floor_radius = 1e-6f * context.accel->length_scale();
  if (s.sppm_initial_radius > 0.0f) {
    const float footprint = median_pixel_footprint(context, f);
    const RadiusRange range =
        meaningful_radius_range(footprint, sources_->scene_radius(), kAutoRadiusPixels * footprint);
    std::string warning;
    const float radius =
        clamp_radius("sppm_initial_radius", s.sppm_initial_radius, range, &warning);
    if (!warning.empty()) control.report_warning(warning);
    for (SppmPixel& p : pixels_) p.radius = std::max(radius, floor_radius);
    return;
  }
  // The distance between the centre rays of a pixel and of its right neighbour, at the depth
  // of the pixel's first hit (0 where the pixel sees nothing).
  const Camera& camera = f.camera;
  const float inv_w = 1.0f / f.full_width, inv_h = 1.0f / f.full_height;
  const auto centre_radius = [&](int px, int py) {
    const Vec2 lens(0.5f, 0.5f);
    const Ray a = generate_camera_ray(camera, (px + 0.5f) * inv_w, (py + 0.5f) * inv_h, lens);
    const Ray b = generate_camera_ray(camera, (px + 1.5f) * inv_w, (py + 0.5f) * inv_h, lens);
    Hit hit;
    if (!context.accel->intersect(a, kVisibleCamera, &hit)) return 0.0f;
    const Vec3 d = (b.origin + hit.t * b.direction) - (a.origin + hit.t * a.direction);
    const float r = kAutoRadiusPixels * length(d);
    return std::isfinite(r) ? r : 0.0f;
  };
  film.for_each_pixel(cancel, [&](int col, int row) {
    pixels_[film.index(col, row)].radius = centre_radius(film.frame_x(col), film.frame_y(row));
  });
  // Pixels that see nothing at their centre take the median radius of the whole frame's pixels
  // that see something, so a render border does not change it (a band of a frame equals the
  // same rows of the full render).
  std::vector<float> seen;
  const bool whole_frame = f.x0 == 0 && f.y0 == 0 && f.x1 == f.full_width && f.y1 == f.full_height;
  if (whole_frame) {
    for (const SppmPixel& p : pixels_)
      if (p.radius > 0.0f) seen.push_back(p.radius);
  } else {
    std::vector<float> frame(static_cast<size_t>(f.full_width) * f.full_height);
    tbb::parallel_for(tbb::blocked_range<int>(0, f.full_height, 1), [&](const auto& rows) {
      for (int py = rows.begin(); py != rows.end(); ++py) {
        if (cancel.load(std::memory_order_relaxed)) return;
        for (int px = 0; px < f.full_width; ++px)
          frame[static_cast<size_t>(py) * f.full_width + px] = centre_radius(px, py);
      }
    });
    for (float r : frame)
      if (r > 0.0f) seen.push_back(r);
  }
  if (cancel.load()) return;
  float fallback = 0.01f * sources_->scene_radius();
  if (!seen.empty()) {
    std::nth_element(seen.begin(), seen.begin() + seen.size() / 2, seen.end());
    fallback = seen[seen.size() / 2];
  }
  for (SppmPixel& p : pixels_)
    p.radius = std::max(p.radius > 0.0f ? p.radius : fallback, floor_radius);
}

bool SppmIntegrator::iterate(const RenderContext& context, Film& film, uint32_t iteration,
                             const std::atomic<bool>& cancel) {
  const RenderSettings& s = *context.settings;
  // Spectral mode: one set of wavelengths for the iteration's photons and camera paths, so a
  // visible point meets photons at its own wavelengths; stratified over the iterations.
  std::optional<SampledWavelengths> wavelengths;
  if (spectral_mode(context))
    wavelengths = sample_wavelengths(
        s, Sampler(s.seed, kWavelengthStream, iteration, static_cast<uint32_t>(s.sppm_iterations)));
  const SampledWavelengths* wl = wavelengths ? &*wavelengths : nullptr;

  auto t0 = Clock::now();
  SppmPhotonPass pass =
      trace_sppm_photons(context, *sources_, iteration, photons_per_iteration_, cancel, wl);
  if (pass.cancelled) return false;
  stats_.rays += pass.rays;
  stats_.photons_recorded = pass.photons.size();
  const PhotonKdTree photons(std::move(pass.photons));
  stats_.peak_photon_bytes = std::max(stats_.peak_photon_bytes, photons.memory_bytes());
  stats_.photon_seconds += seconds_since(t0);

  t0 = Clock::now();
  const float alpha = s.sppm_alpha;
  std::atomic<uint64_t> non_finite{0};
  film.for_each_pixel(cancel, [&](int col, int row) {
    SppmPixel& pixel = pixels_[film.index(col, row)];
    Sampler sampler(s.seed, hash_combine(kCameraStream, film.frame_pixel(col, row)), iteration,
                    static_cast<uint32_t>(s.sppm_iterations));
    const Ray ray = film.camera_ray(film.frame_x(col), film.frame_y(row), sampler);
    const SppmCameraSample c = trace_sppm_camera(context, ray, sampler, photons, pixel.radius, wl);
    if (!is_finite(c.direct) || !is_finite(c.phi)) {
      non_finite.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    pixel.direct += c.direct;
    pixel.alpha += film.coverage(c.alpha, c.holdout);
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
  });
  stats_.camera_seconds += seconds_since(t0);
  if (cancel.load()) return false;
  stats_.non_finite += non_finite.load();
  film.count_non_finite(non_finite.load());
  stats_.photons_emitted += photons_per_iteration_;
  ++stats_.iterations;
  return true;
}

void SppmIntegrator::write_film(Film& film, int iterations) const {
  const int k = std::max(iterations, 1);
  const double emitted = std::max<double>(static_cast<double>(stats_.photons_emitted), 1.0);
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const SppmPixel& p = pixels_[i];
    const double area = kPi * static_cast<double>(p.radius) * p.radius;
    const auto photon_part = [&](float tau) { return static_cast<float>(tau / (emitted * area)); };
    const Vec3 indirect =
        area > 0.0 ? Vec3(photon_part(p.tau.x), photon_part(p.tau.y), photon_part(p.tau.z))
                   : Vec3(0.0f);
    // Indirect is already an average over iterations: scaled by k, it is a sum over iterations
    // like the direct light, which the film resolves as every integrator's pixels.
    const Vec3 passes[kPassCount] = {p.direct, indirect * static_cast<float>(k), Vec3(0.0f),
                                     Vec3(0.0f)};
    film.set_sums(i, p.direct + indirect * static_cast<float>(k), p.alpha, passes);
  }
}

int SppmIntegrator::render(const RenderContext& context, Film& film, const RenderControl& control) {
  const RenderSettings& s = *context.settings;
  const std::atomic<bool>& cancel = cancel_flag(control);
  const auto t0 = Clock::now();
  if (control.first_pass == 0) {
    if (!start_iterative_film(context, film, control)) return 0;
    pixels_.assign(film.pixel_count(), SppmPixel{});
    stats_ = IterationStats{};
    initial_radii(context, film, control);
    if (cancel.load()) return 0;
  }
  return run_iterations(film, control, s.sppm_time, t0, [&](uint32_t pass) {
    if (!iterate(context, film, pass, cancel)) return false;
    write_film(film, pass + 1);
    return true;
  });
}

IntegratorInfo sppm_integrator_info() {
  IntegratorInfo info;
  info.type = IntegratorType::kSppm;
  info.label = "Progressive Photon Mapping";
  info.description =
      "Stochastic progressive photon mapping (Hachisuka & Jensen 2009): camera and photon "
      "passes repeated with a shrinking radius, so the image converges, caustics included; "
      "refines as it renders";
  info.capabilities.name = "SPPM";
  info.capabilities.iterative = true;
  info.capabilities.no_bake_reason =
      "the SPPM integrator converges per pixel of a view and has no view-independent lighting "
      "solution to bake; bake from the photon maps or the radiosity solution";
  info.make = [] { return std::unique_ptr<Integrator>(new SppmIntegrator); };
  return info;
}

}  // namespace photon

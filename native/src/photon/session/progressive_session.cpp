#include "photon/session/progressive_session.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>

#include "photon/render/scene_resources.h"
#include "photon/session/pixel_renderer.h"
#include "photon/session/render_session.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

// A pass aims at this long, so the viewport shows a new image a few times a second and a
// restart (the camera moved) waits for at most one row of it.
constexpr double kPassSeconds = 0.25;
// The first image after a (re)start is a coarse pass whose longer side has about this many
// pixels (every step-th pixel, upscaled), so it shows in a few ms even for a 4K viewport.
constexpr int kCoarseSide = 200;

int coarse_step(const ProgressiveView& view) {
  const int side = std::max(view.x1 - view.x0, view.y1 - view.y0);
  return std::max(1, (side + kCoarseSide - 1) / kCoarseSide);
}

ProgressiveView view_of(const Scene& scene, const RenderSettings& s) {
  ProgressiveView v;
  v.camera = scene.camera;
  v.full_width = s.full_width;
  v.full_height = s.full_height;
  v.x0 = s.x0;
  v.y0 = s.y0;
  v.x1 = s.x1;
  v.y1 = s.y1;
  return v;
}

ProgressiveView sanitized(ProgressiveView v) {
  v.full_width = std::clamp(v.full_width, 1, 65536);
  v.full_height = std::clamp(v.full_height, 1, 65536);
  v.x0 = std::clamp(v.x0, 0, v.full_width - 1);
  v.y0 = std::clamp(v.y0, 0, v.full_height - 1);
  v.x1 = std::clamp(v.x1, v.x0 + 1, v.full_width);
  v.y1 = std::clamp(v.y1, v.y0 + 1, v.full_height);
  return v;
}

// Below this many photons in the coarse map, the full map comes about as fast.
constexpr uint64_t kMinCoarsePhotons = 2000;

}  // namespace

bool coarse_photon_settings(const RenderSettings& settings, RenderSettings* coarse) {
  // SPPM and VCM show photon mapping outside final renders (make_integrator).
  const IntegratorType type = settings.integrator;
  if (type != IntegratorType::kPhotonMap && type != IntegratorType::kSppm &&
      type != IntegratorType::kVcm)
    return false;
  const bool budget = settings.photon_time > 0.0f;
  if (!budget && settings.photons < kCoarsePhotonShare * kMinCoarsePhotons) return false;
  *coarse = settings;
  coarse->photons = std::max<uint64_t>(settings.photons / kCoarsePhotonShare, 1);
  coarse->caustic_photons = settings.caustic_photons / kCoarsePhotonShare;
  coarse->photon_time = settings.photon_time / kCoarsePhotonShare;
  return true;
}

ProgressiveSession::ProgressiveSession(std::shared_ptr<const Scene> scene,
                                       const RenderSettings& settings,
                                       std::shared_ptr<BlasCache> blas_cache, bool quick_first_pass)
    : ProgressiveSession(std::make_shared<ViewportScene>(std::move(scene), std::move(blas_cache)),
                         settings, quick_first_pass) {}

ProgressiveSession::ProgressiveSession(std::shared_ptr<ViewportScene> viewport_scene,
                                       const RenderSettings& settings, bool quick_first_pass)
    : Job("Viewport render"),
      viewport_scene_(std::move(viewport_scene)),
      quick_first_pass_(quick_first_pass) {
  std::vector<std::string> warnings;
  settings_ = sanitized_settings(settings, &warnings);
  add_warnings(warnings);
  view_ = view_of(viewport_scene_->scene(), settings_);
  set_work_total(static_cast<size_t>(settings_.samples));
}

ProgressiveSession::~ProgressiveSession() {
  stop_worker();
}

uint64_t ProgressiveSession::set_view(const ProgressiveView& view) {
  std::lock_guard<std::mutex> lock(mutex_);
  view_ = sanitized(view);
  converged_ = false;
  const uint64_t serial = ++serial_;
  changed_.notify_all();
  return serial;
}

ProgressiveImage ProgressiveSession::image() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return image_;
}

int ProgressiveSession::samples_done() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return image_.view_serial == serial_ && !image_.quick ? image_.samples : 0;
}

bool ProgressiveSession::converged() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return converged_;
}

int ProgressiveSession::wait_for_samples(int samples, double timeout_seconds) const {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, std::chrono::duration<double>(std::max(timeout_seconds, 0.0)), [&] {
    const bool current = image_.view_serial == serial_ && !image_.quick;
    return (current && image_.samples >= samples) || converged_ || finished();
  });
  return image_.view_serial == serial_ && !image_.quick ? image_.samples : 0;
}

bool ProgressiveSession::wait_for_image(double timeout_seconds) const {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, std::chrono::duration<double>(std::max(timeout_seconds, 0.0)), [&] {
    return (!image_.rgba.empty() && image_.view_serial == serial_) || finished();
  });
  return !image_.rgba.empty() && image_.view_serial == serial_;
}

double ProgressiveSession::first_image_seconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return first_image_seconds_;
}

void ProgressiveSession::on_finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  changed_.notify_all();
}

bool ProgressiveSession::interrupted(uint64_t serial) const {
  return cancel_flag().load(std::memory_order_relaxed) ||
         serial_.load(std::memory_order_relaxed) != serial;
}

bool ProgressiveSession::render_pass(const RenderContext& context, const Integrator& integrator,
                                     const ProgressiveView& view, int first, int end,
                                     uint64_t serial) {
  const RenderSettings& s = settings_;
  const int width = view.x1 - view.x0, height = view.y1 - view.y0;
  const PixelFilter filter(s.filter_type, s.filter_width);
  std::atomic<bool> stopped{false};
  std::atomic<uint64_t> non_finite{0};
  // Rows in any order on any thread: a pixel's sum depends only on its own samples, added in
  // sample order, exactly as render_pixels adds them (so N samples in passes equal a render
  // of N samples bit for bit).
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 1), [&](const tbb::blocked_range<int>& r) {
    const size_t n = static_cast<size_t>(width);
    std::vector<Sampler> samplers(n, Sampler(0, 0, 0));
    std::vector<Ray> rays(n);
    std::vector<Hit> hits(n);
    std::unique_ptr<bool[]> found(new bool[n]);
    uint64_t bad = 0;
    for (int row = r.begin(); row < r.end(); ++row) {
      const int py = view.y0 + row;
      float* sums = &accum_[static_cast<size_t>(row) * n * 4];
      for (int k = first; k < end; ++k) {
        if (stopped.load(std::memory_order_relaxed) || interrupted(serial)) {
          stopped = true;
          return;
        }
        for (size_t i = 0; i < n; ++i) {
          const int px = view.x0 + static_cast<int>(i);
          const uint64_t pixel_index = static_cast<uint64_t>(py) * view.full_width + px;
          samplers[i] = Sampler(s.seed, pixel_index, static_cast<uint32_t>(k),
                                static_cast<uint32_t>(s.samples));
          rays[i] = camera_sample_ray(filter, view.camera, view.full_width, view.full_height, px,
                                      py, samplers[i]);
        }
        context.accel->intersect_coherent(rays.data(), n, kVisibleCamera, hits.data(), found.get());
        for (size_t i = 0; i < n; ++i) {
          CameraHit hit;
          hit.found = found[i];
          if (hit.found) hit.hit = hits[i];
          const RadianceSample rs =
              integrator.radiance_from_hit(context, rays[i], hit, samplers[i]);
          const Vec3 radiance = rs.radiance();
          if (!is_finite(radiance) || !is_finite(rs.photon_map)) {
            ++bad;
            continue;
          }
          sums[4 * i + 0] += radiance.x;
          sums[4 * i + 1] += radiance.y;
          sums[4 * i + 2] += radiance.z;
          const float coverage = s.transparent_background ? rs.alpha : 1.0f;
          sums[4 * i + 3] += rs.holdout > 0.0f ? std::max(coverage - rs.holdout, 0.0f) : coverage;
        }
      }
    }
    non_finite += bad;
  });
  non_finite_ += non_finite.load();
  return !stopped.load() && !interrupted(serial);
}

bool ProgressiveSession::render_coarse_pass(const RenderContext& context,
                                            const Integrator& integrator,
                                            const ProgressiveView& view, int step,
                                            uint64_t serial) {
  const RenderSettings& s = settings_;
  const int width = view.x1 - view.x0, height = view.y1 - view.y0;
  const int coarse_w = (width + step - 1) / step, coarse_h = (height + step - 1) / step;
  const PixelFilter filter(s.filter_type, s.filter_width);
  ProgressiveImage image;
  image.width = coarse_w;
  image.height = coarse_h;
  image.samples = 1;
  image.quick = true;
  image.view_serial = serial;
  image.step = step;
  image.rgba.assign(static_cast<size_t>(coarse_w) * coarse_h * 4, 0.0f);
  std::atomic<bool> stopped{false};
  tbb::parallel_for(tbb::blocked_range<int>(0, coarse_h, 1), [&](const tbb::blocked_range<int>& r) {
    const size_t n = static_cast<size_t>(coarse_w);
    std::vector<Sampler> samplers(n, Sampler(0, 0, 0));
    std::vector<Ray> rays(n);
    std::vector<Hit> hits(n);
    std::unique_ptr<bool[]> found(new bool[n]);
    for (int cy = r.begin(); cy < r.end(); ++cy) {
      if (stopped.load(std::memory_order_relaxed) || interrupted(serial)) {
        stopped = true;
        return;
      }
      const int row = cy * step, py = view.y0 + row;
      for (size_t i = 0; i < n; ++i) {
        const int px = view.x0 + static_cast<int>(i) * step;
        const uint64_t pixel_index = static_cast<uint64_t>(py) * view.full_width + px;
        samplers[i] = Sampler(s.seed, pixel_index, 0, static_cast<uint32_t>(s.samples));
        rays[i] = camera_sample_ray(filter, view.camera, view.full_width, view.full_height, px, py,
                                    samplers[i]);
      }
      context.accel->intersect_coherent(rays.data(), n, kVisibleCamera, hits.data(), found.get());
      for (size_t i = 0; i < n; ++i) {
        CameraHit hit;
        hit.found = found[i];
        if (hit.found) hit.hit = hits[i];
        const RadianceSample rs = integrator.radiance_from_hit(context, rays[i], hit, samplers[i]);
        const Vec3 radiance = rs.radiance();
        if (!is_finite(radiance) || !is_finite(rs.photon_map)) continue;
        const float coverage = s.transparent_background ? rs.alpha : 1.0f;
        float* pixel = &image.rgba[(static_cast<size_t>(cy) * n + i) * 4];
        pixel[0] = finite_average(radiance.x, s.exposure);
        pixel[1] = finite_average(radiance.y, s.exposure);
        pixel[2] = finite_average(radiance.z, s.exposure);
        pixel[3] = rs.holdout > 0.0f ? std::max(coverage - rs.holdout, 0.0f) : coverage;
      }
    }
  });
  if (stopped.load() || interrupted(serial)) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  image_ = std::move(image);
  changed_.notify_all();
  return true;
}

bool ProgressiveSession::render_coarse_photon_pass(const RenderContext& context,
                                                   const PrepareControl& control) {
  RenderSettings coarse;
  if (!coarse_photon_settings(settings_, &coarse)) return false;
  RenderContext coarse_context = context;
  coarse_context.settings = &coarse;
  set_status("Coarse photon map");
  std::unique_ptr<Integrator> integrator = make_integrator(settings_.integrator);
  integrator->prepare(coarse_context, control);
  if (cancel_flag()) return false;
  uint64_t serial = 0;
  ProgressiveView view;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    serial = serial_;
    view = view_;
  }
  accum_.assign(static_cast<size_t>(view.x1 - view.x0) * (view.y1 - view.y0) * 4, 0.0f);
  if (!render_pass(coarse_context, *integrator, view, 0, 1, serial)) return false;
  publish(view, 1, true, serial, true);
  return true;
}

void ProgressiveSession::publish(const ProgressiveView& view, int samples, bool quick,
                                 uint64_t serial, bool coarse_photons) {
  ProgressiveImage image;
  image.width = view.x1 - view.x0;
  image.height = view.y1 - view.y0;
  image.samples = samples;
  image.quick = quick;
  image.coarse_photons = coarse_photons;
  image.view_serial = serial;
  image.rgba.resize(accum_.size());
  const float inv_spp = 1.0f / samples;
  const float colour_scale = inv_spp * settings_.exposure;  // as render_pixels scales colour
  for (size_t i = 0; i < accum_.size(); i += 4) {
    image.rgba[i + 0] = finite_average(accum_[i + 0], colour_scale);
    image.rgba[i + 1] = finite_average(accum_[i + 1], colour_scale);
    image.rgba[i + 2] = finite_average(accum_[i + 2], colour_scale);
    image.rgba[i + 3] = accum_[i + 3] * inv_spp;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  image_ = std::move(image);
  // Converged together with the last pass's image, so a reader never sees one without the other.
  if (!quick && samples >= settings_.samples && serial == serial_) converged_ = true;
  changed_.notify_all();
}

void ProgressiveSession::run() {
  const auto t_start = Clock::now();
  const std::atomic<bool>& cancel = cancel_flag();
  auto mark_first_image = [&] {
    std::lock_guard<std::mutex> lock(mutex_);
    if (first_image_seconds_ < 0.0)
      first_image_seconds_ = std::chrono::duration<double>(Clock::now() - t_start).count();
  };
  auto current_view = [&](uint64_t* serial) {
    std::lock_guard<std::mutex> lock(mutex_);
    *serial = serial_;
    return view_;
  };

  run_in_arena(settings_.threads, [&] {
    // Held until the session ends: the scene's instances and resources do not change under it.
    std::lock_guard<std::mutex> scene_lock(viewport_scene_->mutex());
    if (cancel) return;
    std::vector<std::string> warnings;
    if (!viewport_scene_->built()) set_status("Building BVH and lights");
    const SceneResources* resources = viewport_scene_->resources(settings_, &cancel, &warnings);
    add_warnings(warnings);
    if (cancel || !resources) return;
    // The shared resources' context, rendering with this session's settings.
    RenderContext context = resources->context();
    context.settings = &settings_;
    PrepareControl control = prepare_control();

    const IntegratorCapabilities caps = integrator_capabilities(settings_.integrator);
    if (quick_first_pass_) {
      // A first look while photons are traced or radiosity solved: ray-traced direct light,
      // first at a coarse resolution (milliseconds), then one sample of every pixel; the
      // integrator's own passes replace it once it is prepared.
      set_status("Quick preview");
      std::unique_ptr<Integrator> quick = make_integrator(IntegratorType::kRayTrace);
      quick->prepare(context, control);
      uint64_t serial = 0;
      const ProgressiveView view = current_view(&serial);
      const int step = coarse_step(view);
      if (step > 1 && render_coarse_pass(context, *quick, view, step, serial)) mark_first_image();
      if (settings_.integrator != IntegratorType::kRayTrace) {
        accum_.assign(static_cast<size_t>(view.x1 - view.x0) * (view.y1 - view.y0) * 4, 0.0f);
        if (render_pass(context, *quick, view, 0, 1, serial)) {
          publish(view, 1, true, serial);
          mark_first_image();
        }
      }
      if (cancel) return;
      // Then indirect light and caustics from a coarse photon map, traced in a sixteenth of
      // the full map's time; it stays on screen while the full map is traced.
      set_preparing(true);
      render_coarse_photon_pass(context, control);
      if (cancel) return;
    }

    std::unique_ptr<Integrator> integrator = make_integrator(settings_.integrator);
    set_status(caps.stop_early ? "Preparing" : "Rendering");
    set_preparing(true);
    integrator->prepare(context, control);
    set_preparing(false);
    if (cancel) return;
    set_status("Rendering");

    const int target = settings_.samples;
    while (!cancel) {
      uint64_t serial = 0;
      const ProgressiveView view = current_view(&serial);
      accum_.assign(static_cast<size_t>(view.x1 - view.x0) * (view.y1 - view.y0) * 4, 0.0f);
      work_done() = 0;
      int done = 0;
      double seconds_per_sample = 0.0;
      while (done < target && !interrupted(serial)) {
        // One sample first, then as many as fit kPassSeconds, at most doubling each pass.
        int count = 1;
        if (done > 0 && seconds_per_sample > 0.0)
          count = static_cast<int>(kPassSeconds / seconds_per_sample);
        count = std::clamp(count, 1, std::min(std::max(done, 1), target - done));
        const auto t0 = Clock::now();
        if (!render_pass(context, *integrator, view, done, done + count, serial)) break;
        seconds_per_sample = std::chrono::duration<double>(Clock::now() - t0).count() / count;
        done += count;
        publish(view, done, false, serial);
        mark_first_image();
        work_done() = static_cast<size_t>(done);
      }
      if (cancel) break;
      std::unique_lock<std::mutex> lock(mutex_);
      if (serial_ == serial) {
        set_status("Converged");
        // Sleeps until a new view (or cancel, which is polled: Job::cancel does not notify).
        while (serial_ == serial && !cancel) changed_.wait_for(lock, std::chrono::milliseconds(50));
        set_status("Rendering");
      }
    }
  });
  if (non_finite_)
    add_warning(std::to_string(non_finite_) + " samples were NaN or infinite and were dropped");
}

}  // namespace photon

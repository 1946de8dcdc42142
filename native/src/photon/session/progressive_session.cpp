#include "photon/session/progressive_session.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>

#include "photon/integrators/registry.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"

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

}  // namespace

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
  target_ = std::max(make_integrator(settings_.integrator)->passes(settings_), 1);
  set_work_total(static_cast<size_t>(target_));
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

std::unique_ptr<Film> ProgressiveSession::make_film(const ProgressiveView& view, int step) const {
  // The viewport shows Combined only: no light or data passes.
  FilmOptions options = film_options(settings_);
  options.light_passes = false;
  options.data_passes = DataPassSettings{};
  return std::make_unique<Film>(film_frame(view.camera, view.full_width, view.full_height, view.x0,
                                           view.y0, view.x1, view.y1, step),
                                options);
}

bool ProgressiveSession::render_pass(const RenderContext& context, Integrator& integrator,
                                     const ProgressiveView& view, int first, int end,
                                     uint64_t serial, int* done) {
  if (first == 0 || !film_) film_ = make_film(view, 1);
  RenderControl control;
  control.first_pass = first;
  control.end_pass = end;
  control.cancel = &cancel_flag();
  control.interrupted = [this, serial] { return interrupted(serial); };
  control.tile_size = settings_.tile_size;
  control.warn = [this](const std::string& w) { add_warning(w); };
  const uint64_t before = film_->non_finite();
  *done = integrator.render(context, *film_, control);
  non_finite_ += film_->non_finite() - before;
  return *done > first && !interrupted(serial);
}

bool ProgressiveSession::render_coarse_pass(const RenderContext& context, Integrator& integrator,
                                            const ProgressiveView& view, int step,
                                            uint64_t serial) {
  const std::unique_ptr<Film> coarse = make_film(view, step);
  Film& film = *coarse;
  RenderControl control;
  control.end_pass = 1;
  control.cancel = &cancel_flag();
  control.interrupted = [this, serial] { return interrupted(serial); };
  control.tile_size = settings_.tile_size;
  if (integrator.render(context, film, control) < 1 || interrupted(serial)) return false;
  ProgressiveImage image;
  image.width = film.width();
  image.height = film.height();
  image.samples = 1;
  image.quick = true;
  image.view_serial = serial;
  image.step = step;
  image.rgba.resize(film.pixel_count() * 4);
  film.resolve_rgba(FilmRect{0, 0, film.width(), film.height()}, 1, image.rgba.data());
  std::lock_guard<std::mutex> lock(mutex_);
  image_ = std::move(image);
  changed_.notify_all();
  return true;
}

bool ProgressiveSession::render_coarse_preparation_pass(const RenderContext& context,
                                                        const PrepareControl& control) {
  std::unique_ptr<Integrator> integrator = make_integrator(settings_.integrator);
  RenderSettings coarse;
  if (!integrator->coarse_settings(settings_, &coarse)) return false;
  RenderContext coarse_context = context;
  coarse_context.settings = &coarse;
  set_status("Coarse photon map");
  integrator->prepare(coarse_context, control);
  if (cancel_flag()) return false;
  uint64_t serial = 0;
  ProgressiveView view;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    serial = serial_;
    view = view_;
  }
  int done = 0;
  if (!render_pass(coarse_context, *integrator, view, 0, 1, serial, &done)) return false;
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
  image.rgba.resize(film_->pixel_count() * 4);
  film_->resolve_rgba(FilmRect{0, 0, film_->width(), film_->height()}, samples, image.rgba.data());
  std::lock_guard<std::mutex> lock(mutex_);
  image_ = std::move(image);
  // Converged together with the last pass's image, so a reader never sees one without the other.
  if (!quick && samples >= target_ && serial == serial_) converged_ = true;
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
      // Integrators whose own first image comes late (after a preparation, or a whole
      // iteration) show one ray-traced sample of every pixel meanwhile.
      int done = 0;
      if ((caps.prepares || caps.iterative) &&
          render_pass(context, *quick, view, 0, 1, serial, &done)) {
        publish(view, 1, true, serial);
        mark_first_image();
      }
      if (cancel) return;
      // Then the integrator's own coarse first look (indirect light and caustics from a photon
      // map traced in a sixteenth of the full map's time); it stays on screen while the full
      // preparation runs.
      set_preparing(true);
      render_coarse_preparation_pass(context, control);
      if (cancel) return;
    }

    std::unique_ptr<Integrator> integrator = make_integrator(settings_.integrator);
    set_status(caps.stop_early ? "Preparing" : "Rendering");
    set_preparing(true);
    integrator->prepare(context, control);
    set_preparing(false);
    if (cancel) return;
    set_status("Rendering");

    const int target = target_;
    while (!cancel) {
      uint64_t serial = 0;
      const ProgressiveView view = current_view(&serial);
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
        int now_done = 0;
        if (!render_pass(context, *integrator, view, done, done + count, serial, &now_done)) break;
        seconds_per_sample =
            std::chrono::duration<double>(Clock::now() - t0).count() / (now_done - done);
        done = now_done;
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

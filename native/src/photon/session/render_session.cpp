#include "photon/session/render_session.h"

#include <pmmintrin.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>
#include <xmmintrin.h>

#include "photon/integrators/pixel_integrator.h"
#include "photon/integrators/registry.h"
#include "photon/integrators/render_params.h"
#include "photon/render/camera_clip_check.h"
#include "photon/session/quick_preview.h"
#include "photon/session/scene_resources.h"

namespace photon {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Embree recommends flush-to-zero and denormals-are-zero in every thread that traces rays:
// denormal arithmetic is slow and never changes an image.
void set_flush_denormals() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

class FlushDenormalsObserver : public tbb::task_scheduler_observer {
 public:
  explicit FlushDenormalsObserver(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) {
    observe(true);
  }
  ~FlushDenormalsObserver() override { observe(false); }
  void on_scheduler_entry(bool) override { set_flush_denormals(); }
};

// Between two images of an iterating integrator handed to Blender: writing a large frame's
// passes takes a while, and short iterations would spend their time there.
constexpr double kPublishSeconds = 1.0;
constexpr size_t kProgressSteps = 1000;

// More render threads than a few per core only add scheduling overhead; far more than TBB's
// worker limit (65,536 in oneTBB 2021) makes TBB warn and later crashes the process.
constexpr int kMaxThreadsPerCore = 4;

int machine_cores() {
  return std::max(1, tbb::info::default_concurrency());
}

int thread_limit() {
  return kMaxThreadsPerCore * machine_cores();
}

RenderSettings sanitize(RenderSettings s, std::vector<std::string>* warnings) {
  s.full_width = std::clamp(s.full_width, 1, 65536);
  s.full_height = std::clamp(s.full_height, 1, 65536);
  s.x0 = std::clamp(s.x0, 0, s.full_width - 1);
  s.y0 = std::clamp(s.y0, 0, s.full_height - 1);
  s.x1 = std::clamp(s.x1, s.x0 + 1, s.full_width);
  s.y1 = std::clamp(s.y1, s.y0 + 1, s.full_height);
  if (s.threads > thread_limit()) {
    if (warnings)
      warnings->push_back("threads = " + std::to_string(s.threads) +
                          " is more than this machine can use: clamped to " +
                          std::to_string(thread_limit()) + " (at most " +
                          std::to_string(kMaxThreadsPerCore) + " per core on " +
                          std::to_string(machine_cores()) + " cores)");
    s.threads = thread_limit();
  }
  // Every parameter into its schema's range (after the machine's thread limit, which is the
  // tighter bound and says why).
  clamp_render_params(&s, warnings);
  const IntegratorCapabilities caps = integrator_capabilities(s.integrator);
  if (s.spectral && !caps.spectral) {
    if (warnings)
      warnings->push_back(std::string("Spectral rendering is not available with the ") + caps.name +
                          " integrator: rendering in RGB");
    s.spectral = false;
  }
  return s;
}

}  // namespace

RenderSettings sanitized_settings(const RenderSettings& settings,
                                  std::vector<std::string>* warnings) {
  return sanitize(settings, warnings);
}

int arena_threads(int threads) {
  // TBB never runs more threads than the host allows (Blender's -t sets this): a bigger arena
  // would only make TBB print a warning, and the stats would name threads that never ran.
  const auto allowed = static_cast<int>(std::min<size_t>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism), 1 << 20));
  if (threads <= 0) return std::max(1, std::min(tbb::this_task_arena::max_concurrency(), allowed));
  return std::max(1, std::min({threads, thread_limit(), allowed}));
}

int run_in_arena(int threads, const std::function<void()>& fn) {
  set_flush_denormals();
  const int n = arena_threads(threads);
  tbb::task_arena arena(n);
  FlushDenormalsObserver observer(arena);
  arena.execute(fn);
  return n;
}

RenderSession::RenderSession(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
                             std::shared_ptr<BlasCache> blas_cache)
    : Job("Render"), scene_(std::move(scene)), blas_cache_(std::move(blas_cache)) {
  std::vector<std::string> warnings;
  settings_ = sanitize(settings, &warnings);
  add_warnings(warnings);
  image_.assign(static_cast<size_t>(region_width()) * region_height() * 4, 0.0f);
  set_work_total(kProgressSteps);
}

RenderSession::~RenderSession() {
  stop_worker();
}

std::vector<Tile> RenderSession::take_tiles(double timeout_seconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  tiles_ready_.wait_for(lock, std::chrono::duration<double>(std::max(timeout_seconds, 0.0)),
                        [this] { return !queue_.empty() || finished(); });
  std::vector<Tile> out(std::make_move_iterator(queue_.begin()),
                        std::make_move_iterator(queue_.end()));
  queue_.clear();
  return out;
}

bool RenderSession::take_preview(std::vector<float>* rgba) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!preview_ready_) return false;
  preview_ready_ = false;
  *rgba = std::move(preview_);
  preview_.clear();
  return true;
}

RenderStats RenderSession::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

std::vector<float> RenderSession::image() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return image_;
}

void RenderSession::on_finished() {
  // Under the lock, so a take_tiles() between its check of finished() and its wait still wakes.
  std::lock_guard<std::mutex> lock(mutex_);
  tiles_ready_.notify_all();
}

void RenderSession::run() {
  const std::atomic<bool>& cancel = cancel_flag();
  set_flush_denormals();
  const int threads = arena_threads(settings_.threads);
  tbb::task_arena arena(threads);
  FlushDenormalsObserver observer(arena);

  std::vector<std::string> warnings;
  set_status(scene_->textures.empty() ? "Building BVH and lights"
                                      : "Converting textures, building BVH and lights");
  auto t0 = Clock::now();
  std::unique_ptr<SceneResources> resources;
  arena.execute([&] {
    resources =
        std::make_unique<SceneResources>(*scene_, settings_, &warnings, &cancel, blas_cache_.get());
  });
  const double texture_seconds = resources->textures().seconds();
  const double build_seconds = seconds_since(t0) - texture_seconds;
  if (cancel) return;
  const std::string clip_warning = camera_clip_warning(scene_->camera, resources->accel());
  if (!clip_warning.empty()) warnings.push_back(clip_warning);
  const RenderContext& context = resources->context();
  std::unique_ptr<Integrator> integrator = make_integrator(settings_.integrator);

  if (quick_preview_) {
    set_status("Quick preview");
    std::vector<float> preview;
    arena.execute([&] { preview = render_quick_preview(context, cancel); });
    if (cancel) return;
    std::lock_guard<std::mutex> lock(mutex_);
    // The assembled image starts as the preview: a cancelled render still shows it where no
    // tile was finished.
    image_ = preview;
    preview_ = std::move(preview);
    preview_ready_ = true;
  }

  set_status("Preparing");
  t0 = Clock::now();
  const Clock::time_point budget_start = t0;  // Time Limit counts from here
  PrepareControl control = prepare_control();
  // Kept in order after the scene's warnings; added to the session's once prepared.
  control.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
  set_preparing(true);
  PreparedStateStats prepared_state;
  arena.execute([&] {
    prepare_with_state_files(context, resources->textures(), settings_.integrator, integrator.get(),
                             control, prepared_files_, &prepared_state, &warnings);
  });
  set_preparing(false);
  const double prepare_seconds = seconds_since(t0);
  if (cancel) return;

  add_warnings(warnings);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_.build_seconds = build_seconds;
    stats_.texture_seconds = texture_seconds;
    stats_.textures = resources->textures().size();
    stats_.textures_reused = resources->textures().reused();
    stats_.prepare_seconds = prepare_seconds;
    stats_.unique_triangles = resources->accel().triangle_count();
    stats_.instances = resources->accel().instance_count();
    stats_.bvh_count = resources->accel().blas_count();
    stats_.bvh_reused = resources->accel().blas_reused();
    stats_.lights = resources->lights().size();
    stats_.threads = threads;
    stats_.integrator = integrator->prepare_stats();
    stats_.prepared_state = prepared_state;
  }
  if (prepared_files_.prepare_only) return;
  set_status("Rendering");
  t0 = Clock::now();
  render_film(context, *integrator, arena, budget_start);
  std::lock_guard<std::mutex> lock(mutex_);
  stats_.render_seconds = seconds_since(t0);  // render_film counted the camera samples
  stats_.iterations = integrator->render_stats();
}

int RenderSession::render_film(const RenderContext& context, Integrator& integrator,
                               tbb::task_arena& arena, Clock::time_point start) {
  Film film(film_frame(scene_->camera, settings_.full_width, settings_.full_height, settings_.x0,
                       settings_.y0, settings_.x1, settings_.y1),
            film_options(settings_));
  RenderControl control;
  control.first_pass = 0;
  control.end_pass = integrator.passes(settings_);
  control.cancel = &cancel_flag();
  control.tile_size = settings_.tile_size;
  control.status = [this](const std::string& s) { set_status(s); };
  control.warn = [this](const std::string& w) { add_warning(w); };
  set_work_total(kProgressSteps);
  control.progress = [this](float fraction) {
    // Never backwards: tiles finish out of order.
    const size_t steps = static_cast<size_t>(std::clamp(fraction, 0.0f, 1.0f) * kProgressSteps);
    size_t done = work_done().load();
    while (steps > done && !work_done().compare_exchange_weak(done, steps)) {
    }
  };
  // A rectangle short of the whole film is a finished tile, handed over at once. The whole
  // film is an integrator's image after an iteration: it replaces the one before, at most one
  // waits, and it is handed over when first, last, or kPublishSeconds after the one before.
  const FilmRect whole{0, 0, film.width(), film.height()};
  Clock::time_point last_publish{};
  bool published_any = false;
  int pending_passes = 0;  // the whole film's passes not yet handed over (0: none)
  const auto deliver = [&](const FilmRect& rect, int passes) {
    Tile tile;
    tile.x = rect.x;
    tile.y = rect.y;
    tile.width = rect.width;
    tile.height = rect.height;
    tile.rgba.resize(static_cast<size_t>(rect.width) * rect.height * 4);
    film.resolve_rgba(rect, passes, tile.rgba.data());
    tile.passes = film.resolve_passes(rect, passes);
    return tile;
  };
  control.update = [&](const FilmRect& rect, int passes, bool last) {
    const bool whole_film =
        rect.x == 0 && rect.y == 0 && rect.width == whole.width && rect.height == whole.height;
    if (!whole_film) {
      deliver_tile(deliver(rect, passes));
      return;
    }
    pending_passes = passes;
    const double since = std::chrono::duration<double>(Clock::now() - last_publish).count();
    if (!published_any || last || since >= kPublishSeconds) {
      publish_whole(deliver(rect, passes));
      published_any = true;
      pending_passes = 0;
      last_publish = Clock::now();
    }
  };
  const double limit = settings_.time_limit;
  const IntegratorInfo& info = integrator_info(settings_.integrator);
  const bool iterative = info.capabilities.iterative;
  AdaptiveSampling adaptive = adaptive_sampling(settings_);
  if (adaptive.threshold > 0.0f && iterative) {
    add_warning(std::string("Noise Threshold is not used by ") + info.label +
                ": every pixel takes part in every iteration");
    adaptive = AdaptiveSampling{};
  }
  if (adaptive.threshold > 0.0f) film.enable_adaptive_sampling();
  int done = 0;
  if (iterative) {
    // Iterative integrators stop between iterations, within their own limit too.
    if (limit > 0.0) control.time_limit = std::max(limit - seconds_since(start), 1e-3);
    arena.execute([&] { done = integrator.render(context, film, control); });
  } else if (limit <= 0.0 && adaptive.threshold <= 0.0f) {
    arena.execute([&] { done = integrator.render(context, film, control); });
  } else {
    done =
        render_passes_in_rounds(context, integrator, film, control, arena, start, limit, adaptive);
  }
  // The last complete iteration is always handed over.
  if (pending_passes > 0) publish_whole(deliver(whole, pending_passes));
  std::lock_guard<std::mutex> lock(mutex_);
  stats_.non_finite_samples += film.non_finite();
  stats_.camera_samples =
      film.adaptive() ? film.total_samples() : static_cast<uint64_t>(film.pixel_count()) * done;
  return done;
}

int RenderSession::render_passes_in_rounds(const RenderContext& context, Integrator& integrator,
                                           Film& film, RenderControl control,
                                           tbb::task_arena& arena, Clock::time_point start,
                                           double limit, const AdaptiveSampling& adaptive) {
  // Rounds of passes over the whole film, each stratified among its own samples (the pixels'
  // sample count is not known ahead; consecutive rounds together are as well stratified as
  // one). With a Time Limit the first round is one pass; each next one what the time left allows
  // at the last round's speed (at most twice the passes before, so tiles keep arriving), and
  // none once not one pass fits. With adaptive sampling rounds end where pixels are judged, and
  // the render ends early once every pixel has converged.
  const int total = control.end_pass;
  const auto progress = control.progress;
  const bool timed = limit > 0.0;
  control.stratify_each_call = true;
  int done = 0, round = 1;
  bool converged = false;
  while (done < total) {
    control.first_pass = done;
    control.end_pass = timed ? std::min(total, done + round) : total;
    if (adaptive.threshold > 0.0f)
      control.end_pass = std::min(control.end_pass, adaptive.next_check(done));
    control.progress = [&, first = done](float fraction) {
      if (!progress) return;
      const double samples = (first + fraction * (control.end_pass - first)) / total;
      progress(
          static_cast<float>(timed ? std::max(samples, seconds_since(start) / limit) : samples));
    };
    const Clock::time_point round_start = Clock::now();
    int reached = done;
    arena.execute([&] { reached = integrator.render(context, film, control); });
    if (reached < control.end_pass) break;  // cancelled: the passes before stay
    const double per_pass = seconds_since(round_start) / (reached - done);
    done = reached;
    if (adaptive.threshold > 0.0f && done < total && adaptive.next_check(done - 1) == done &&
        film.update_convergence(adaptive.threshold) == 0) {
      converged = true;
      break;
    }
    if (!timed) continue;
    const double left = limit - seconds_since(start);
    const double fit = per_pass > 0.0 ? left / per_pass : static_cast<double>(total);
    if (fit < 1.0) break;
    round = static_cast<int>(std::min<double>({fit, 2.0 * done, static_cast<double>(total)}));
    round = std::max(round, 1);
  }
  // The data passes take every sample of a pixel in one go, which only a single round of all
  // passes gave them: they are rendered now for the passes reached (camera rays and first hits
  // only, a small part of a sample's cost).
  if (film.data_floats() > 0 && (total > 1 || film.adaptive()) && done > 0 && !control.stopped()) {
    control.report_status("Data passes");
    RenderSettings reached = *context.settings;
    reached.samples = done;
    RenderContext data_context = context;
    data_context.settings = &reached;
    bool finished = false;
    arena.execute([&] { finished = render_data_passes(data_context, film, control); });
    if (finished && control.update)
      control.update(FilmRect{0, 0, film.width(), film.height()}, done, true);
  }
  if (timed && done < total && !converged)
    add_warning("Time Limit reached after " + std::to_string(done) + " of " +
                std::to_string(total) + " samples per pixel");
  return done;
}

void RenderSession::publish_whole(Tile tile) {
  {
    // An image not yet taken is superseded: at most one waits, whatever the poller's pace.
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.clear();
  }
  deliver_tile(std::move(tile));
}

void RenderSession::deliver_tile(Tile tile) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (int row = 0; row < tile.height; ++row) {
    const float* src = &tile.rgba[static_cast<size_t>(row) * tile.width * 4];
    float* dst = &image_[(static_cast<size_t>(tile.y + row) * region_width() + tile.x) * 4];
    std::copy(src, src + tile.width * 4, dst);
  }
  queue_.push_back(std::move(tile));
  tiles_ready_.notify_all();
}

}  // namespace photon

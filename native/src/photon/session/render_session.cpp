#include "photon/session/render_session.h"

#include <pmmintrin.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>
#include <xmmintrin.h>

#include "photon/integrators/render_params.h"
#include "photon/render/scene_resources.h"
#include "photon/scene/camera_clip_check.h"
#include "photon/session/data_passes.h"
#include "photon/session/pixel_renderer.h"
#include "photon/session/quick_preview.h"

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
  if (s.spectral && s.integrator == IntegratorType::kRadiosity && warnings)
    warnings->push_back("Spectral rendering is not available with radiosity: rendering in RGB");
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
  const int ts = settings_.tile_size;
  tile_count_ = static_cast<size_t>((region_width() + ts - 1) / ts) *
                static_cast<size_t>((region_height() + ts - 1) / ts);
  set_work_total(tile_count_);
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
  PrepareControl control = prepare_control();
  // Kept in order after the scene's warnings; added to the session's once prepared.
  control.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
  set_preparing(true);
  const bool iterative = integrator_capabilities(settings_.integrator).iterative;
  PreparedStateStats prepared_state;
  if (!iterative) {
    arena.execute([&] {
      prepare_with_state_files(context, resources->textures(), settings_.integrator,
                               integrator.get(), control, prepared_files_, &prepared_state,
                               &warnings);
    });
  } else if (!prepared_files_.load.empty() || !prepared_files_.save.empty()) {
    warnings.push_back(
        "prepared-state files are used by the PHOTON_MAP integrator only; this "
        "render's iterative integrator ignores them");
  }
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
  if (iterative) {
    run_iterative(context, arena);
    return;
  }

  const int ts = settings_.tile_size;
  const int tiles_x = (region_width() + ts - 1) / ts;
  std::atomic<size_t>& tiles_done = work_done();
  t0 = Clock::now();
  // Tiles are handed out in reading order from a shared counter, so they appear top to bottom
  // in Blender's image editor. Which thread renders a tile does not change its pixels.
  std::atomic<size_t> next_tile{0};
  arena.execute([&] {
    tbb::parallel_for(0, threads, [&](int) {
      for (size_t i = next_tile++; i < tile_count_ && !cancel; i = next_tile++) {
        Tile tile;
        tile.x = static_cast<int>(i % tiles_x) * ts;
        tile.y = static_cast<int>(i / tiles_x) * ts;
        tile.width = std::min(ts, region_width() - tile.x);
        tile.height = std::min(ts, region_height() - tile.y);
        const int rows = render_tile(context, *integrator, &tile);
        if (rows < tile.height) {
          // Cancelled inside the tile: its finished rows are kept (their samples are complete).
          if (rows > 0) {
            tile.height = rows;
            tile.rgba.resize(static_cast<size_t>(rows) * tile.width * 4);
            if (!tile.passes.empty())
              tile.passes.resize(static_cast<size_t>(rows) * tile.width * kPassFloats);
            if (!tile.data.empty())
              tile.data.resize(static_cast<size_t>(rows) * tile.width *
                               data_pass_pixel_floats(settings_.data_passes));
            deliver_tile(std::move(tile));
          }
          return;
        }
        deliver_tile(std::move(tile));
        ++tiles_done;
      }
    });
  });

  {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_.render_seconds = seconds_since(t0);
    stats_.camera_samples =
        static_cast<uint64_t>(tiles_done.load()) == tile_count_
            ? static_cast<uint64_t>(region_width()) * region_height() * settings_.samples
            : 0;
  }
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

int RenderSession::render_tile(const RenderContext& context, const Integrator& integrator,
                               Tile* tile) {
  tile->rgba.assign(static_cast<size_t>(tile->width) * tile->height * 4, 0.0f);
  if (settings_.light_passes)
    tile->passes.assign(static_cast<size_t>(tile->width) * tile->height * kPassFloats, 0.0f);
  const int data_floats = data_pass_pixel_floats(settings_.data_passes);
  if (data_floats)
    tile->data.assign(static_cast<size_t>(tile->width) * tile->height * data_floats, 0.0f);
  uint64_t bad = 0;
  int rows = 0;
  render_pixels(context, integrator, settings_.x0 + tile->x, settings_.y0 + tile->y, tile->width,
                tile->height, tile->rgba.data(), cancel_flag(), &bad,
                settings_.light_passes ? tile->passes.data() : nullptr,
                data_floats ? tile->data.data() : nullptr, &rows);
  if (bad) {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_.non_finite_samples += bad;
  }
  return rows;
}

}  // namespace photon

// Runs one render on a background thread: builds the BVH, prepares the integrator, renders tiles
// in parallel with TBB and hands finished tiles to whoever polls (the Blender add-on, the CLI).
#pragma once

#include <tbb/task_arena.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/registry.h"
#include "photon/render/blas_cache.h"
#include "photon/scene/scene.h"
#include "photon/session/job.h"
#include "photon/session/prepared_state.h"

namespace photon {

// A finished block of pixels: RGBA float rows, top row first, position relative to the render
// region's top-left corner. A render cancelled in the middle of a tile hands over the tile's
// finished rows (a shorter tile).
struct Tile {
  int x = 0, y = 0, width = 0, height = 0;
  std::vector<float> rgba;
  // The film's other passes by name (film.h): the light passes with RenderSettings::light_passes,
  // the data passes and Cryptomatte layers of RenderSettings::data_passes.
  std::vector<PassImage> passes;
  // The pass called `name`, or null.
  const PassImage* pass(const std::string& name) const {
    for (const PassImage& p : passes)
      if (p.name == name) return &p;
    return nullptr;
  }
};

// `settings` clamped to what the renderer accepts (also used by lighting bakes); a clamp the
// user should know about (threads beyond what the machine can use) adds a warning.
RenderSettings sanitized_settings(const RenderSettings& settings,
                                  std::vector<std::string>* warnings = nullptr);
// The arena size for `threads` (0 = all cores), at most a few threads per core.
int arena_threads(int threads);
// Runs `fn` in a TBB arena of arena_threads(threads) threads whose threads flush denormals,
// as Embree recommends. Returns the thread count used.
int run_in_arena(int threads, const std::function<void()>& fn);

struct RenderStats {
  double texture_seconds = 0.0;  // converting images (or finding them converted)
  size_t textures = 0;
  size_t textures_reused = 0;  // found in the persistent texture cache
  double build_seconds = 0.0;  // BVH, lights and emissive triangles (textures excluded)
  double prepare_seconds = 0.0;
  double render_seconds = 0.0;
  uint64_t camera_samples = 0;
  uint64_t non_finite_samples = 0;  // dropped NaN/inf radiance values
  size_t unique_triangles = 0;
  size_t instances = 0;
  size_t bvh_count = 0;
  size_t bvh_reused = 0;  // of bvh_count, taken from the BlasCache (Persistent Data)
  size_t lights = 0;
  int threads = 0;
  PrepareStats integrator;            // the integrator's prepare_stats()
  PreparedStateStats prepared_state;  // a prepared-state file loaded or saved
  IterationStats iterations;  // an iterating integrator's (SPPM, VCM); iterations = 0 otherwise
};

class RenderSession : public Job {
 public:
  // With a `blas_cache`, unchanged meshes keep their BVH from earlier renders (Persistent Data).
  RenderSession(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
                std::shared_ptr<BlasCache> blas_cache = nullptr);
  ~RenderSession() override;  // cancels and waits for the worker thread

  // start(), wait(), cancel(), stop_preparation() (Esc during photon tracing), progress (of
  // photon tracing, then of the tiles), status and warnings come from Job.

  // Finished tiles since the last call; waits up to `timeout_seconds` for at least one.
  std::vector<Tile> take_tiles(double timeout_seconds);

  // Before start(): render a quick preview of the whole region (quick_preview.h) once the BVH is
  // built and before the integrator's preparation, for a user watching the render.
  void set_quick_preview(bool enabled) { quick_preview_ = enabled; }
  // Before start(): load the integrator's preparation from a file and/or save it to one, and
  // optionally stop once prepared (prepared_state.h).
  void set_prepared_state(const PreparedStateFiles& files) { prepared_files_ = files; }
  // The preview (RGBA rows of the region, top row first) the first time it is asked for after
  // it was rendered; false before then and after.
  bool take_preview(std::vector<float>* rgba);

  RenderStats stats() const;
  const RenderSettings& settings() const { return settings_; }  // as sanitized
  int region_width() const { return settings_.x1 - settings_.x0; }
  int region_height() const { return settings_.y1 - settings_.y0; }
  // The render region assembled from all finished tiles (RGBA, top row first).
  std::vector<float> image() const;

 private:
  void run() override;
  void on_finished() override;
  // Renders the integrator's passes into a film of the region and hands over what finishes:
  // tiles as they complete, the whole region after each iteration (replacing the one before).
  // Returns the passes every pixel holds. With Time Limit, the budget counts from `start`.
  int render_film(const RenderContext& context, Integrator& integrator, tbb::task_arena& arena,
                  std::chrono::steady_clock::time_point start);
  // Time Limit and adaptive sampling for pixel integrators: renders the passes in rounds over
  // the whole film, stops before a round that would pass `limit` seconds (> 0) since `start`,
  // and judges the pixels' noise between rounds (`adaptive`, threshold > 0); returns the passes
  // rendered (at least one unless cancelled).
  int render_passes_in_rounds(const RenderContext& context, Integrator& integrator, Film& film,
                              RenderControl control, tbb::task_arena& arena,
                              std::chrono::steady_clock::time_point start, double limit,
                              const AdaptiveSampling& adaptive);
  void deliver_tile(Tile tile);
  // Hands over an image of the whole region, dropping one not yet taken.
  void publish_whole(Tile tile);

  std::shared_ptr<const Scene> scene_;
  std::shared_ptr<BlasCache> blas_cache_;  // may be null
  RenderSettings settings_;
  bool quick_preview_ = false;
  PreparedStateFiles prepared_files_;

  mutable std::mutex mutex_;  // queue_, image_, stats_
  std::condition_variable tiles_ready_;
  std::deque<Tile> queue_;
  std::vector<float> preview_;
  bool preview_ready_ = false;
  std::vector<float> image_;
  RenderStats stats_;
};

}  // namespace photon

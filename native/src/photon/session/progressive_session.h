// Progressive rendering for Blender's viewport and previews: the scene's resources are built
// and its integrator prepared once, then the whole frame is rendered in passes of a few
// samples each, accumulated, and shown between passes. A new view (the viewport camera moved,
// the region resized) restarts the accumulation without rebuilding or re-preparing anything.
// Sessions on one ViewportScene share its resources: the next session (new settings, moved
// objects) only prepares its integrator again.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/registry.h"
#include "photon/render/blas_cache.h"
#include "photon/scene/scene.h"
#include "photon/session/job.h"
#include "photon/session/viewport_scene.h"

namespace photon {

// What is rendered: a camera and the frame it fills, with the pixel rectangle [x0, x1) x
// [y0, y1) (y downwards) actually rendered (a viewport's render border).
struct ProgressiveView {
  Camera camera;
  int full_width = 64, full_height = 64;
  int x0 = 0, y0 = 0, x1 = 64, y1 = 64;
};

// The accumulated image at one moment.
struct ProgressiveImage {
  int width = 0, height = 0;  // of the view's rectangle
  std::vector<float> rgba;    // width * height * 4, top row first; empty before the first pass
  int samples = 0;            // samples per pixel averaged in `rgba`
  // True while `rgba` is a quick first look shown before the integrator's preparation (photon
  // maps, a radiosity solve) has finished: direct light of a ray-traced pass, then, for photon
  // mapping, a pass over a coarse photon map (`coarse_photons`).
  bool quick = false;
  bool coarse_photons = false;
  uint64_t view_serial = 0;  // the set_view() call this image belongs to (0: the initial view)
  // A coarse quick image has one pixel per step x step block of the view's rectangle (width
  // and height are then the coarse image's, rounded up), to be shown scaled up.
  int step = 1;
};

class ProgressiveSession : public Job {
 public:
  // Renders `scene` (its camera is the initial view) up to settings.samples samples per
  // pixel. `blas_cache` keeps unchanged meshes' BVHs between sessions (may be null).
  // With `quick_first_pass`, an integrator with a long preparation is preceded by one
  // ray-traced sample so an image shows within the time of a BVH build.
  ProgressiveSession(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
                     std::shared_ptr<BlasCache> blas_cache = nullptr, bool quick_first_pass = true);
  // Renders `viewport_scene`, building its resources only if no earlier session did. At most
  // one session renders a ViewportScene at a time (a second one waits for the first to end).
  ProgressiveSession(std::shared_ptr<ViewportScene> viewport_scene, const RenderSettings& settings,
                     bool quick_first_pass = true);
  ~ProgressiveSession() override;  // cancels and joins the worker

  // Restarts accumulation from the new view at the next row; returns its serial.
  uint64_t set_view(const ProgressiveView& view);
  // The latest completed pass (a pass interrupted by set_view or cancel is never shown).
  ProgressiveImage image() const;
  int samples_done() const;
  // The passes the view converges at: samples per pixel, or the integrator's iterations.
  int target_samples() const { return target_; }
  // True once the current view has all its samples (the worker then sleeps until a new view).
  bool converged() const;
  // Blocks until the current view has at least `samples` samples (or is converged, or the
  // session ended) or `timeout_seconds` passed; returns samples_done().
  int wait_for_samples(int samples, double timeout_seconds) const;
  // Blocks until an image (quick ones included) of the current view exists, the session
  // ended, or `timeout_seconds` passed; true when there is one.
  bool wait_for_image(double timeout_seconds) const;
  // Seconds from start() to the first image of any kind (quick or not); negative before.
  double first_image_seconds() const;

 private:
  void run() override;
  void on_finished() override;
  // Cycles' viewport "start resolution": sample 0 of every step-th pixel of every step-th
  // row, standing for its step x step block, published as a coarse quick image (the view's
  // film untouched); false when interrupted.
  bool render_coarse_pass(const RenderContext& context, Integrator& integrator,
                          const ProgressiveView& view, int step, uint64_t serial);
  // Renders passes [first, end) of `view` into film_ (a first of 0 starts it afresh); false
  // when interrupted. `done` receives the passes the film then holds.
  bool render_pass(const RenderContext& context, Integrator& integrator,
                   const ProgressiveView& view, int first, int end, uint64_t serial, int* done);
  void publish(const ProgressiveView& view, int samples, bool quick, uint64_t serial,
               bool coarse_photons = false);
  // One pass of every pixel with the integrator's coarse first look (a photon map of a
  // sixteenth of the photons), published as a quick image; false when it has none or was
  // interrupted.
  bool render_coarse_preparation_pass(const RenderContext& context, const PrepareControl& control);
  bool interrupted(uint64_t serial) const;
  // The film of `view` (its whole rectangle, every step-th pixel).
  std::unique_ptr<Film> make_film(const ProgressiveView& view, int step) const;

  std::shared_ptr<ViewportScene> viewport_scene_;
  RenderSettings settings_;
  bool quick_first_pass_;

  mutable std::mutex mutex_;  // view_, serial_, image_, first_image_seconds_
  mutable std::condition_variable changed_;
  ProgressiveView view_;
  std::atomic<uint64_t> serial_{0};
  ProgressiveImage image_;
  bool converged_ = false;
  double first_image_seconds_ = -1.0;

  int target_ = 1;
  std::unique_ptr<Film> film_;  // worker only: the current view's sums
  uint64_t non_finite_ = 0;     // worker only
};

}  // namespace photon

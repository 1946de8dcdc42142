// The interface every rendering algorithm implements (pbrt-v4's Integrator): prepare once per
// render, then render passes of the frame into a film. Most integrators answer one camera sample
// at a time and inherit the one pixel loop from PixelIntegrator (pixel_integrator.h); those that
// refine whole frames in iterations (SPPM, VCM) render on their own. Sessions only call these
// methods and never ask which integrator runs.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "photon/base/math.h"
#include "photon/base/prepare_control.h"
#include "photon/base/rng.h"
#include "photon/film/film.h"
#include "photon/integrators/iteration_stats.h"
#include "photon/integrators/prepare_stats.h"
#include "photon/integrators/render_settings.h"
#include "photon/lights/lights.h"
#include "photon/render/accel.h"
#include "photon/render/render_context.h"
#include "photon/scene/scene.h"

namespace photon {

class EmissiveMeshes;
class EmitterSet;
class PreparedStateReader;
class PreparedStateWriter;
class TextureSet;

// What one render() call is to do and whom it tells.
struct RenderControl {
  // The passes to render: samples per pixel [first_pass, end_pass) for pixel integrators,
  // iterations for iterative ones. A pass's random numbers depend on its index only, so passes
  // rendered in several calls equal the same passes rendered in one, bit for bit.
  int first_pass = 0;
  int end_pass = 1;
  const std::atomic<bool>* cancel = nullptr;
  // Another reason to stop at once (the viewport's view changed); may be empty.
  std::function<bool()> interrupted;
  // Film pixels that are final after `passes` passes: a tile's rows, or the whole film after an
  // iteration (`last`: no more will follow in this call). May be empty. Called from the
  // rendering threads, one call at a time per rectangle.
  std::function<void(const FilmRect& rect, int passes, bool last)> update;
  // The fraction of this call's work done; may be empty.
  std::function<void(float fraction)> progress;
  // What the integrator does now and what the user should know; may be empty.
  std::function<void(const std::string& status)> status;
  std::function<void(const std::string& warning)> warn;
  int tile_size = 64;  // film pixels per tile side, for integrators that render in tiles
  // A time budget for this call (0: none), for integrators that stop between iterations.
  double time_limit = 0.0;
  // Pixel integrators: this call's passes are stratified among themselves (Sampler's blocks),
  // for calls whose passes add up to a count not known ahead.
  bool stratify_each_call = false;

  bool stopped() const {
    return (cancel && cancel->load(std::memory_order_relaxed)) || (interrupted && interrupted());
  }
  void report_status(const std::string& s) const {
    if (status) status(s);
  }
  void report_warning(const std::string& w) const {
    if (warn) warn(w);
  }
};

// The points of a lighting bake, on the side each is baked: what Integrator::prepare_bake sees.
struct BakePointSet {
  size_t count = 0;
  const Vec3* positions = nullptr;
  const Vec3* normals = nullptr;   // shading normal of the baked side
  const uint8_t* valid = nullptr;  // 0: the point is not shaded (may be null: all are)
  // The interaction of point i on its baked side; false when there is none. Thread-safe.
  std::function<bool(size_t i, SurfaceInteraction* si)> interaction;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Runs once before pixels are rendered (photon tracing, radiosity solve, ...). Long
  // preparations poll `control` and return early when asked to.
  virtual void prepare(const RenderContext& context, const PrepareControl& control) {
    (void)context;
    (void)control;
  }
  // Statistics of the preparation (and of prepare_bake), for the UI and logs.
  virtual PrepareStats prepare_stats() const { return {}; }
  // Integrators whose preparation can be shared (integrator_capabilities: shares_preparation)
  // write what prepare() computed that pixels read to a prepared-state file
  // (prepared_state_file.h), and read it back instead of preparing: the pixels are then the
  // same bits as after prepare(). load_prepared returns false with `error` and leaves the
  // integrator unprepared when the payload is damaged.
  virtual void save_prepared(PreparedStateWriter* out) const { (void)out; }
  virtual bool load_prepared(PreparedStateReader* in, std::string* error) {
    (void)in;
    if (error) *error = "this integrator does not load a prepared state";
    return false;
  }
  // A lower bound of the rays a render of `settings` traces besides `camera_samples` camera
  // rays (final gathers, photons, a radiosity solve), which decides how much a BVH build may
  // cost (session/scene_resources.h).
  virtual uint64_t extra_rays(const RenderSettings& settings, uint64_t camera_samples) const {
    (void)settings, (void)camera_samples;
    return 0;
  }
  // The passes a final render of `settings` takes: samples per pixel, or iterations.
  virtual int passes(const RenderSettings& settings) const { return settings.samples; }
  // Renders passes [control.first_pass, control.end_pass) of `film`, which holds the earlier
  // ones (a call with first_pass 0 starts the film afresh). Returns the passes every pixel of
  // the film then holds: end_pass, fewer when an iterative integrator stopped early (cancel,
  // its time limit), or first_pass when a pass was left incomplete. Polls `control`.
  virtual int render(const RenderContext& context, Film& film, const RenderControl& control) = 0;
  // Statistics of the last render(), for the UI and logs (the iterations of SPPM and VCM).
  virtual IterationStats render_stats() const { return {}; }
  // The settings of a quick first look at this integrator's image while its full preparation
  // runs (a photon map of a sixteenth of the photons), or false when it has none.
  virtual bool coarse_settings(const RenderSettings& settings, RenderSettings* coarse) const {
    (void)settings, (void)coarse;
    return false;
  }
  // View-independent radiance leaving a diffuse surface point (emission plus reflected light,
  // averaged over outgoing directions as a Lambertian surface would), for baking lighting into
  // Blender data. `hit` is the point on the scene, `si` its interaction. Integrators without a
  // view-independent solution return false.
  virtual bool baked_radiance(const RenderContext& context, const Hit& hit,
                              const SurfaceInteraction& si, Sampler& sampler,
                              Vec3* radiance) const {
    (void)context, (void)hit, (void)si, (void)sampler, (void)radiance;
    return false;
  }
  // A cheap estimate of baked_radiance, only to choose which side of a point is baked.
  virtual bool baked_probe(const RenderContext& context, const Hit& hit,
                           const SurfaceInteraction& si, Sampler& sampler, Vec3* radiance) const {
    return baked_radiance(context, hit, si, sampler, radiance);
  }
  // Called once before baked_radiance with every point the bake shades, so work shared between
  // nearby points (an irradiance cache) is placed among them. Polls `control`.
  virtual void prepare_bake(const RenderContext& context, const BakePointSet& points,
                            const PrepareControl& control) {
    (void)context, (void)points, (void)control;
  }
};

}  // namespace photon

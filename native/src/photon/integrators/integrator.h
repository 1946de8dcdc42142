// The interface every rendering algorithm implements (after Nori): prepare once per render,
// then answer radiance queries for camera rays from any thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "photon/base/math.h"
#include "photon/base/rng.h"
#include "photon/integrators/data_pass_settings.h"
#include "photon/integrators/photon_map/photon_map_params.h"
#include "photon/integrators/prepare_stats.h"
#include "photon/integrators/radiosity/radiosity_params.h"
#include "photon/integrators/sampling_params.h"
#include "photon/integrators/sppm/sppm_params.h"
#include "photon/lights/lights.h"
#include "photon/render/accel.h"
#include "photon/scene/scene.h"

namespace photon {

class EmissiveMeshes;
class EmitterSet;
class PreparedStateReader;
class PreparedStateWriter;
class TextureSet;

// What a render is asked to do: the frame, and each algorithm's parameters (declared once in
// their schemas; render_params.h lists them all and clamps them). The parameter structs are
// bases so every field keeps its flat name (settings.photons), which is also its name in the
// schema, the Blender property and the command line.
struct RenderSettings : SamplingParams,
                        FilmParams,
                        PerformanceParams,
                        PhotonMapParams,
                        RadiosityParams,
                        SppmParams,
                        SpectralParams {
  int full_width = 64, full_height = 64;  // whole frame in pixels
  // Pixel rectangle to render (Blender's render border), [x0, x1) x [y0, y1), y downwards.
  int x0 = 0, y0 = 0, x1 = 64, y1 = 64;
  bool transparent_background = false;  // from the scene's Film > Transparent
  bool light_passes = false;     // also write the Direct / Indirect / Caustics / Photon Map passes
  DataPassSettings data_passes;  // Depth, Mist, Normal, ... (session/data_passes.h)
};

// Read-only state shared by all threads during a render.
struct RenderContext {
  const Scene* scene = nullptr;
  const Accel* accel = nullptr;
  const LightSet* lights = nullptr;
  const RenderSettings* settings = nullptr;
  const EmissiveMeshes* emissive = nullptr;  // emissive triangles as lights (may be empty)
  const TextureSet* textures = nullptr;      // the scene's image textures (may be null)
  const EmitterSet* emitters = nullptr;      // lamps, emissive triangles and world as emitters
};

// What one camera sample sees, split into light passes whose sum is the Combined image.
struct RadianceSample {
  Vec3 direct;         // emission, direct light, and lights / world seen through specular paths
  Vec3 indirect;       // light that bounced off at least one diffuse surface
  Vec3 caustic;        // light that reached a diffuse surface through specular paths only
  Vec3 photon_map;     // a view of the stored photons (not light; not part of Combined)
  float alpha = 0.0f;  // 1 when the camera ray hit something that is not background
  // Share of the sample taken out by holdouts (the path's throughput into them): the pixel's
  // alpha is reduced by it whether or not the film is transparent, as in Cycles.
  float holdout = 0.0f;
  Vec3 radiance() const { return direct + indirect + caustic; }
};

// Reports and controls a long preparation (photon tracing, a radiosity solve).
struct PrepareControl {
  const std::atomic<bool>* cancel = nullptr;      // abandon the render
  const std::atomic<bool>* stop_early = nullptr;  // finish this phase now, keep what is done
  std::function<void(const std::string& status, float fraction)> progress;
  std::function<void(const std::string& warning)> warn;

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
  bool should_stop() const {
    return cancelled() || (stop_early && stop_early->load(std::memory_order_relaxed));
  }
  void report(const std::string& status, float fraction) const {
    if (progress) progress(status, fraction);
  }
};

// The first intersection of a camera ray, traced beforehand together with its neighbours.
struct CameraHit {
  bool found = false;
  Hit hit;
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
  // Radiance arriving along a camera ray whose first hit is already known (the renderer traces
  // camera rays in coherent batches). Must be thread-safe and deterministic in `sampler`.
  virtual RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                           const CameraHit& first, Sampler& sampler) const = 0;
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

std::unique_ptr<Integrator> make_integrator(IntegratorType type);

// What an integrator type can do, asked of the factory by the sessions and the add-on instead of
// testing for particular types.
struct IntegratorCapabilities {
  const char* name = "";  // as the Python enum names it: "PHOTON_MAP"
  // prepare() does work of its own before the first pixel (photon maps, a radiosity solve).
  bool prepares = false;
  // baked_radiance gives a view-independent solution that lighting bakes read.
  bool bake = false;
  const char* no_bake_reason = "";  // for the user, when bake is false
  // prepare() ends early on PrepareControl::stop_early and the render goes on with what was
  // prepared, while the preparation's status starts with stop_early_status ("" = all of it).
  bool stop_early = false;
  const char* stop_early_status = "";
  const char* stop_early_effect = "";  // for the user: what the render goes on with
  // prepare()'s result can be saved and loaded (save_prepared / load_prepared), so renders of
  // bands of one frame share one preparation.
  bool shares_preparation = false;
  // Renders whole frames in iterations (SPPM) instead of answering radiance queries: the render
  // session runs it through session/iterative_render.cpp, refining the image after each
  // iteration. Per-sample sessions (viewport, previews) use make_integrator's stand-in.
  bool iterative = false;
};

IntegratorCapabilities integrator_capabilities(IntegratorType type);

}  // namespace photon

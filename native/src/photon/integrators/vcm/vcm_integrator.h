// Vertex connection and merging (Georgiev, Krivanek, Davidovic & Slusallek 2012) as an iterative
// integrator beside SPPM. Each iteration:
//  1. traces N = vcm_light_paths light subpaths (vcm_light_paths.h), storing their
//     vertices and splatting their connections to the camera (light tracing);
//  2. hashes the light vertices in a grid of the iteration's merging radius (vcm_grid.h);
//  3. traces one camera subpath per pixel (vcm_camera_paths.h): emission met, next-event
//     estimation, connections to the vertices of light subpath (pixel index mod N), and merging
//     with every light vertex within the radius, all weighed by one balance-heuristic MIS.
// The radius shrinks as r_i = r_1 i^((alpha - 1) / 2) (the paper's eq. 8 with vcm_alpha), so
// merging's bias vanishes while it keeps its share of the weights. vcm_mode keeps only the
// connections (bidirectional path tracing) or only merging (progressive photon mapping, no
// MIS, merging at the first connectible vertex).
//
// The pixel value after k iterations is the mean of the k iterations' estimates (camera sample
// plus the splats the pixel received).
//
// Determinism: light subpaths and their splats are traced in fixed chunks and applied in chunk
// order (vcm_light_paths.h); the grid is built by a counting sort in vertex order; each pixel's
// camera subpath draws from its own (seed, pixel, iteration) stream and is summed by one thread.
// The image after k iterations is the same bits for any thread count, and a render border
// renders the same bits as the same pixels of the full frame (the automatic merging radius is
// measured over the whole frame, pixel streams and light-path pairing use full-frame indices).
//
// Supported: pinhole perspective cameras (other cameras render with SPPM, with a warning), every
// emitter (lights/emitter.h; lamps with a radius as spheres). The data passes (Depth,
// Normal, Cryptomatte, ...) are rendered once from the camera rays before the first iteration,
// as for SPPM. Not rendered: the light passes (left black, with a warning), holdouts, shadow
// catchers and ray-visibility flags other than the camera's.
//
// Memory: one iteration's light subpaths are held until its camera pass has read them; when
// vcm_light_paths would not fit half of the memory available (estimated from a pilot,
// vcm_light_paths.h), fewer are traced per iteration, with a warning. A requested initial
// radius is clamped into the range where merging means something (merge_radius.h).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/registry.h"
#include "photon/integrators/sppm/sppm_integrator.h"
#include "photon/integrators/vcm/vcm_camera_model.h"
#include "photon/integrators/vcm/vcm_common.h"

namespace photon {

// Share of the memory available at the start that one iteration's light subpaths may use.
constexpr double kVcmMemoryFraction = 0.5;

class VcmIntegrator final : public Integrator {
 public:
  VcmIntegrator();
  ~VcmIntegrator() override;
  // The emitters as light subpaths start from them, and the scene's extent.
  void prepare(const RenderContext& context, const PrepareControl& control) override;
  int passes(const RenderSettings& settings) const override { return settings.vcm_iterations; }
  // Iterations [first_pass, end_pass) over the film, as SppmIntegrator::render.
  int render(const RenderContext& context, Film& film, const RenderControl& control) override;
  IterationStats render_stats() const override;
  // The merging radius of iteration i (0-based) of the current film.
  float radius(int iteration) const;

 private:
  bool iterate(const RenderContext& context, Film& film, uint32_t iteration,
               const std::atomic<bool>& cancel);
  // light_paths_: vcm_light_paths, or fewer with a warning when one iteration's light subpaths
  // would not fit kVcmMemoryFraction of the available memory.
  void plan_light_paths(const RenderContext& context, const RenderControl& control);

  std::unique_ptr<VcmLights> lights_;
  PhotonFrame scene_frame_;
  std::unique_ptr<VcmCamera> camera_;  // of the film being rendered
  float initial_radius_ = 0.0f;
  float alpha_ = 2.0f / 3.0f;
  uint64_t light_paths_ = 1;  // per iteration
  IterationStats stats_;
  // Cameras light tracing cannot reach (orthographic, depth of field) render with SPPM.
  std::unique_ptr<SppmIntegrator> fallback_;
  RenderSettings fallback_settings_;  // SPPM's settings with VCM's budget
  RenderContext fallback_context_;
  bool use_fallback_ = false;
};

IntegratorInfo vcm_integrator_info();

}  // namespace photon

// Vertex connection and merging (Georgiev, Krivanek, Davidovic & Slusallek 2012) as an iterative
// integrator beside SPPM. Each iteration:
//  1. traces N = sppm_photons_per_iteration light subpaths (vcm_light_paths.h), storing their
//     vertices and splatting their connections to the camera (light tracing);
//  2. hashes the light vertices in a grid of the iteration's merging radius (vcm_grid.h);
//  3. traces one camera subpath per pixel (vcm_camera_paths.h): emission met, next-event
//     estimation, connections to the vertices of light subpath (pixel index mod N), and merging
//     with every light vertex within the radius, all weighed by one balance-heuristic MIS.
// The radius shrinks as r_i = r_1 i^((alpha - 1) / 2) (the paper's eq. 8 with sppm_alpha), so
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
// Supported: pinhole perspective cameras (the session renders other cameras with SPPM and says
// so), every emitter kind of emission_pdf.h (lamps with a radius as spheres). The data passes
// (Depth, Normal, Cryptomatte, ...) come from the render session, which renders them once from
// the camera rays before the first iteration, as for SPPM (session/iterative_render.cpp). Not
// rendered: the light passes (left black, with a warning), holdouts, shadow catchers and
// ray-visibility flags other than the camera's.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/iterative_renderer.h"
#include "photon/integrators/vcm/vcm_camera_model.h"
#include "photon/integrators/vcm/vcm_common.h"

namespace photon {

class VcmRenderer final : public IterativeRenderer {
 public:
  // Renders the region of context.settings (x0, y0, x1, y1 of the full frame).
  explicit VcmRenderer(const RenderContext& context, std::vector<std::string>* warnings = nullptr);
  ~VcmRenderer() override;
  // Whether the scene's camera is one VCM renders (pinhole perspective).
  static bool supports_camera(const RenderContext& context);

  bool iterate(const std::atomic<bool>& cancel) override;
  int iterations() const override { return stats_.iterations; }
  const SppmStats& stats() const override { return stats_; }
  void write_image(float* rgba, float* passes = nullptr) const override;
  // The merging radius of iteration i (0-based).
  float radius(int iteration) const;

 private:
  float automatic_radius() const;

  const RenderContext& context_;
  int width_, height_;
  VcmCamera camera_;
  std::unique_ptr<VcmLights> lights_;
  float initial_radius_ = 0.0f;
  std::vector<Vec3> sum_;     // per pixel: the iterations' estimates summed
  std::vector<float> alpha_;  // coverage summed over iterations
  SppmStats stats_;
};

}  // namespace photon

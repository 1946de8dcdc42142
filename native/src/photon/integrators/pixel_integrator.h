// The integrators that answer one camera sample at a time (ray tracing, photon mapping,
// radiosity) and the one loop that feeds them pixels (pbrt-v4's ImageTileIntegrator): tiles of
// the film in parallel (TBB), handed out in reading order; per row of a tile and per sample, the
// row's camera rays traced together as one coherent Embree stream, then each pixel's path
// finished by the integrator and added to the film, with the data passes from the same rays.
// Random numbers depend only on (seed, pixel, sample), never on the tile or thread.
#pragma once

#include "photon/integrators/integrator.h"

namespace photon {

class PixelIntegrator : public Integrator {
 public:
  // The pixel loop over passes [first_pass, end_pass) (samples per pixel). Each finished tile
  // (or, when stopped, its finished rows) is reported through control.update. Data passes are
  // traced when the film keeps them and the call renders all of a pixel's samples.
  int render(const RenderContext& context, Film& film, const RenderControl& control) override;

  // Radiance arriving along a camera ray whose first hit is already known. Must be
  // thread-safe and deterministic in `sampler`.
  virtual RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                           const CameraHit& first, Sampler& sampler) const = 0;
};

// The pixel loop without an integrator: only the film's data passes, from the camera rays of
// context.settings->samples samples, for integrators that render whole frames in iterations
// (SPPM, VCM). False when stopped (rows unfinished).
bool render_data_passes(const RenderContext& context, Film& film, const RenderControl& control);

}  // namespace photon

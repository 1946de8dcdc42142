// An integrator that renders the whole frame in iterations (SPPM, VCM): the render session
// (session/iterative_render.cpp) runs any of them the same way.
#pragma once

#include <atomic>
#include <cstdint>

#include "photon/integrators/sppm/sppm_stats.h"

namespace photon {

class IterativeRenderer {
 public:
  virtual ~IterativeRenderer() = default;
  // Runs the next iteration. False when cancelled during it: the renderer is then not to be
  // iterated or read again.
  virtual bool iterate(const std::atomic<bool>& cancel) = 0;
  virtual int iterations() const = 0;
  virtual const SppmStats& stats() const = 0;
  // The image after iterations(): RGBA of the region's rows, top first, and the light passes
  // (pixel_renderer.h's kPassFloats per pixel) when `passes` is given.
  virtual void write_image(float* rgba, float* passes = nullptr) const = 0;
};

}  // namespace photon

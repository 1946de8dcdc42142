// A coarse image of the render region, ready within about a second, shown while the slow
// stages of a render (photon tracing, radiance precompute, irradiance cache) still run.
#pragma once

#include <atomic>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/ray_trace/ray_trace_integrator.h"

namespace photon {

// Camera samples per preview block, and the most camera samples a preview takes: a 1080p frame
// is previewed in blocks of 8 x 8 pixels.
constexpr int kPreviewSamples = 4;
constexpr int kPreviewSampleBudget = 131072;

// Pixels per preview block side for a region of `width` x `height`, so that the preview takes
// at most about kPreviewSampleBudget samples.
int preview_block_size(int width, int height);

// Direct light and specular paths (Whitted ray tracing, kPreviewSamples samples spread over each
// block)
// over the region [x0, x1) x [y0, y1) of context.settings' frame, each block filled with its
// sample: RGBA rows, top row first, (x1 - x0) * (y1 - y0) * 4 floats. Rows are spread over the
// calling TBB arena. Returns an empty vector when `cancel` is set before it is done.
std::vector<float> render_quick_preview(const RenderContext& context,
                                        const std::atomic<bool>& cancel);

}  // namespace photon

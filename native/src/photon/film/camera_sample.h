// The camera sample of a pixel and the value a pixel's sum of samples resolves to: one place for
// both, so every renderer (tiles, progressive passes, iterative integrators) makes the same ray
// for a (seed, pixel, sample) triple and the same pixel from the same sum.
#pragma once

#include "photon/base/math.h"
#include "photon/base/rng.h"
#include "photon/scene/camera.h"
#include "photon/scene/pixel_filter.h"

namespace photon {

// A pixel's value from its sample sum: samples are finite, but their sum can still overflow (a
// 1e38 W lamp), so an average that left the float range is the largest float, never inf (NaN
// is 0).
float finite_average(float sum, float inv_spp);

// The camera ray of sample `sampler` (already seeded with (seed, pixel, sample)) through pixel
// (px, py) of a full_width x full_height frame seen by `camera`: the pixel filter's jitter,
// then the lens.
Ray camera_sample_ray(const PixelFilter& filter, const Camera& camera, int full_width,
                      int full_height, int px, int py, Sampler& sampler);

}  // namespace photon

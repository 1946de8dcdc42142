// The per-pixel sampling loop shared by the render session, the CLI and the benchmarks.
#pragma once

#include <atomic>
#include <cstdint>

#include "photon/base/rng.h"
#include "photon/integrators/integrator.h"
#include "photon/scene/pixel_filter.h"

namespace photon {

// Renders the pixels [x, x + width) x [y, y + height) of the full frame (y downwards) into
// `rgba` (width * height * 4 floats, top row first), averaging context.settings->samples
// samples per pixel. For each row and sample index, the row's camera rays are traced together
// as one coherent Embree stream; the rest of each path is traced ray by ray.
// Random numbers depend only on (seed, pixel, sample), never on the block being rendered.
// Returns false, leaving the block incomplete, as soon as `cancel` is set; the rows finished by
// then are complete and their count goes to `rows_done` (optional). Non-finite samples are
// dropped and counted in `non_finite`.
// `passes` (optional, width * height * kPassFloats floats) receives the light passes per pixel:
// Direct RGB, Indirect RGB, Caustics RGB, Photon Map RGB; Combined RGB is their light sum.
// `data` (optional, width * height * data_pass_pixel_floats(settings->data_passes) floats)
// receives the data passes (data_passes.h) from the same camera rays.
constexpr int kPassCount = 4;
// A pixel's value from its sample sum: samples are finite, but their sum can still overflow (a
// 1e38 W lamp), so an average that left the float range is the largest float, never inf (NaN
// is 0). Every renderer (tiles, progressive passes) writes pixels through it.
float finite_average(float sum, float inv_spp);
// The camera ray of sample `sampler` (already seeded with (seed, pixel, sample)) through pixel
// (px, py) of a full_width x full_height frame seen by `camera`: the pixel filter's jitter,
// then the lens. Every renderer (tiles, progressive passes) draws camera samples here, so a
// (seed, pixel, sample) triple gives the same ray in all of them.
Ray camera_sample_ray(const PixelFilter& filter, const Camera& camera, int full_width,
                      int full_height, int px, int py, Sampler& sampler);

constexpr int kPassFloats = 3 * kPassCount;
// Only the data passes of the pixels [x, x + width) x [y, y + height), from the camera rays and
// first hits render_pixels() would trace: the same floats as its `data`, for renderers whose
// integrator does not answer per camera sample (SPPM). False when cancelled (rows unfinished).
bool render_data_passes(const RenderContext& context, int x, int y, int width, int height,
                        float* data, const std::atomic<bool>& cancel);
bool render_pixels(const RenderContext& context, const Integrator& integrator, int x, int y,
                   int width, int height, float* rgba, const std::atomic<bool>& cancel,
                   uint64_t* non_finite, float* passes = nullptr, float* data = nullptr,
                   int* rows_done = nullptr);

}  // namespace photon

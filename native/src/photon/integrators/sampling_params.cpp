#include "photon/integrators/sampling_params.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "photon/integrators/registry.h"
#include "photon/spectral/sampled_spectrum.h"

// Schema entries name only the fields they set (designated initializers); the rest keep
// ParamSpec's defaults, which is what -Wmissing-field-initializers would flag.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace photon {

const ParamSchema<SamplingParams>& sampling_schema() {
  using S = SamplingParams;
  // The integrators' items come from the registry, in the order the user sees them.
  std::vector<ParamEnumItem> integrators;
  int max_integrator = 0;
  for (const IntegratorInfo& info : integrator_registry()) {
    const int value = static_cast<int>(info.type);
    integrators.push_back({info.capabilities.name, info.label, info.description, value});
    max_integrator = std::max(max_integrator, value);
  }
  static const ParamSchema<S> schema{
      "sampling",
      "Sampling",
      "",
      {
          param(&S::integrator, {.name = "integrator",
                                 .label = "Integrator",
                                 .description = "Rendering algorithm",
                                 .min = 0,
                                 .max = static_cast<double>(max_integrator),
                                 .items = integrators}),
          param(&S::samples, {.name = "samples",
                              .label = "Samples",
                              .description = "Camera samples per pixel",
                              .min = 1,
                              .max = 1 << 20,
                              .soft_max = 4096,
                              .ui = {.column = 1}}),
          param(&S::preview_samples,
                {.name = "preview_samples",
                 .label = "Viewport Samples",
                 .description = "Camera samples per pixel in the 3D viewport's Rendered mode "
                                "and in material, light and world previews",
                 .min = 1,
                 .max = 1 << 20,
                 .soft_max = 4096,
                 .ui = {.column = 1, .text = "Viewport"}}),
          param(&S::max_depth, {.name = "max_depth",
                                .label = "Max Depth",
                                .description = "Maximum number of mirror and glass bounces",
                                .min = 0,
                                .max = 1024,
                                .soft_max = 64,
                                .ui = {.column = 1}}),
          // Any 64-bit seed is valid; Blender's integer properties stop at 2^31 - 1.
          param(&S::seed, {.name = "seed",
                           .label = "Seed",
                           .description = "Random seed; the same seed renders the same image",
                           .min = 0,
                           .max = 9007199254740992.0}),  // 2^53: exact as a double
          param(&S::time_limit,
                {.name = "time_limit",
                 .label = "Time Limit",
                 .description = "Stop a final render once this many seconds have passed since "
                                "its preparation began (photon tracing included), every pixel "
                                "with the same samples, fewer than Samples if need be; 0 "
                                "renders all samples. The image then depends on the machine's "
                                "speed",
                 .min = 0,
                 .max = 86400 * 7,
                 .soft_max = 3600,
                 .subtype = "TIME_ABSOLUTE",
                 .unit = "TIME",
                 .ui = {.column = 1}}),
          param(&S::adaptive_sampling,
                {.name = "adaptive_sampling",
                 .label = "Noise Threshold",
                 .description = "Adaptive sampling, as Cycles': a final render's pixels stop "
                                "taking samples once their noise is below the threshold, so "
                                "easy pixels finish early (ray tracing, photon mapping and "
                                "radiosity)",
                 .ui = {.column = 2}}),
          param(&S::adaptive_threshold,
                {.name = "adaptive_threshold",
                 .label = "Noise Threshold",
                 .description = "Noise level at which a pixel stops sampling, Cycles' measure "
                                "(lower: less noise, more samples); 0 chooses it from Samples",
                 .min = 0.0,
                 .max = 1.0,
                 .soft_min = 0.001,
                 .precision = 4,
                 .ui = {.column = 2, .text = "Threshold", .active_if = "adaptive_sampling"}}),
          param(&S::adaptive_min_samples,
                {.name = "adaptive_min_samples",
                 .label = "Min Samples",
                 .description = "Samples every pixel takes before it may stop; 0 chooses them "
                                "from the noise threshold, as Cycles does",
                 .min = 0,
                 .max = 1 << 20,
                 .soft_max = 4096,
                 .ui = {.column = 2, .active_if = "adaptive_sampling"}}),
      }};
  return schema;
}

AdaptiveSampling adaptive_sampling(const SamplingParams& p) {
  AdaptiveSampling a;
  if (!p.adaptive_sampling) return a;
  float threshold = p.adaptive_threshold;
  if (threshold <= 0.0f) threshold = std::max(0.001f, 1.0f / static_cast<float>(p.samples));
  a.min_samples = p.adaptive_min_samples > 0
                      ? std::max(4, p.adaptive_min_samples)
                      : std::max(4, static_cast<int>(std::ceil(16.0f / std::pow(threshold, 0.3f))));
  a.threshold = threshold * 5.0f;
  return a;
}

int AdaptiveSampling::next_check(int done) const {
  // Cycles filters after sample s (0-based) when s > min_samples and s + 1 is a multiple of the
  // step.
  int n = (done / kStep + 1) * kStep;
  while (n - 1 <= min_samples) n += kStep;
  return n;
}

const ParamSchema<FilmParams>& film_schema() {
  using S = FilmParams;
  static const ParamSchema<S> schema{
      "film",
      "Film",
      "",
      {
          param(&S::exposure, {.name = "exposure",
                               .label = "Exposure",
                               .description = "Image brightness scale: pixel colours are "
                                              "multiplied by it (Cycles' film exposure)",
                               .min = 0.0,
                               .max = 10.0}),
          param(&S::filter_type,
                {.name = "filter_type",
                 .label = "Pixel Filter",
                 .description = "Pixel filter type, importance sampled as in Cycles",
                 .min = 0,
                 .max = 2,
                 .items = {{"BOX", "Box", "Box filter", static_cast<int>(PixelFilterType::kBox)},
                           {"GAUSSIAN", "Gaussian", "Gaussian filter",
                            static_cast<int>(PixelFilterType::kGaussian)},
                           {"BLACKMAN_HARRIS", "Blackman-Harris", "Blackman-Harris filter",
                            static_cast<int>(PixelFilterType::kBlackmanHarris)}}}),
          param(&S::filter_width,
                {.name = "filter_width",
                 .label = "Width",
                 .description = "Pixel filter width in pixels, as Cycles': Gaussian and "
                                "Blackman-Harris reach 1.5 and 1 widths from the pixel centre; "
                                "Box is that wide (1 covers the pixel, 0.01 samples its centre). "
                                "In Blender, with Cycles enabled, only Box's width is read here",
                 .min = kMinFilterWidth,
                 .max = kMaxFilterWidth,
                 .subtype = "PIXEL"}),
      }};
  return schema;
}

const ParamSchema<PerformanceParams>& performance_schema() {
  using S = PerformanceParams;
  static const ParamSchema<S> schema{
      "performance",
      "Performance",
      "",
      {
          // The machine's own limit (4 threads per core) is applied by the render session.
          param(&S::threads,
                {.name = "threads",
                 .label = "Threads",
                 .description = "Render threads (0 = all cores); more than 4 per core are not used",
                 .min = 0,
                 .max = 4096,
                 .soft_max = 256}),
          param(&S::tile_size, {.name = "tile_size",
                                .label = "Tile Size",
                                .description = "Width and height of the render tiles in pixels",
                                .min = 4,
                                .max = 4096,
                                .soft_min = 8,
                                .subtype = "PIXEL"}),
      }};
  return schema;
}

const ParamSchema<SpectralParams>& spectral_schema() {
  using S = SpectralParams;
  static const ParamSchema<S> schema{
      "spectral",
      "Spectral",
      "",
      {
          param(&S::spectral,
                {.name = "spectral",
                 .label = "Spectral",
                 .description = "Render with sampled wavelengths instead of RGB (hero-wavelength "
                                "sampling over 360-830 nm), so glass with an Abbe number "
                                "disperses light into colours; radiosity stays RGB"}),
          param(&S::spectral_samples,
                {.name = "spectral_samples",
                 .label = "Wavelengths",
                 .description = "Wavelengths each path carries (stratified over the spectrum): "
                                "more gives less colour noise per sample at a small cost",
                 .min = 1,
                 .max = spectral::kSpectrumSamples,
                 .ui = {.active_if = "spectral"}}),
      }};
  return schema;
}

}  // namespace photon

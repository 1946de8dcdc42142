// Parameters every integrator shares: which algorithm, camera sampling, and how the work is
// split over threads and tiles. Declared once in their schemas (sampling_params.cpp).
#pragma once

#include <cstdint>

#include "photon/base/param_schema.h"
#include "photon/scene/pixel_filter.h"

namespace photon {

enum class IntegratorType : uint8_t { kRayTrace, kPhotonMap, kRadiosity, kSppm, kVcm };

struct SamplingParams {
  IntegratorType integrator = IntegratorType::kPhotonMap;
  int samples = 64;  // camera samples per pixel
  // Samples per pixel of the 3D viewport's Rendered mode and of material/light/world previews
  // (the progressive session stops there; Cycles' "Viewport" samples).
  int preview_samples = 16;
  int max_depth = 8;  // specular bounces after the camera ray
  uint64_t seed = 0;
  // > 0: a final render stops adding samples once this many seconds have passed since its
  // preparation began (Cycles' Time Limit, which leaves out scene synchronisation).
  float time_limit = 0.0f;
  // Adaptive sampling as Cycles' Noise Threshold: a final render's pixel stops taking samples
  // once its estimated relative error is below adaptive_threshold (0: Cycles' automatic
  // max(0.001, 1 / samples)), after at least adaptive_min_samples (0: Cycles' automatic count).
  bool adaptive_sampling = false;
  float adaptive_threshold = 0.01f;
  int adaptive_min_samples = 0;
};

// The noise threshold and minimum samples adaptive sampling uses for `p`, as Cycles derives
// them from its settings (scene/integrator.cpp, get_adaptive_sampling): the threshold scaled by
// Cycles' factor 5, the automatic minimum 16 / threshold^0.3 (0.1 -> 32, 0.01 -> 64), at least 4.
struct AdaptiveSampling {
  float threshold = 0.0f;
  int min_samples = 0;
  // Pixels are judged after every `step` samples once more than min_samples were taken.
  static constexpr int kStep = 16;
  // The first sample count above `done` after which pixels are judged.
  int next_check(int done) const;
};
AdaptiveSampling adaptive_sampling(const SamplingParams& p);

// The film: how camera samples are spread around their pixel (pixel_filter.h) and how the pixel
// values are scaled, as Cycles' Film settings.
struct FilmParams {
  PixelFilterType filter_type = PixelFilterType::kBox;
  // Box: the width of the box around the pixel's centre (1 covers the pixel; 0.01 samples its
  // centre). Gaussian and Blackman-Harris: Cycles' width, a third and a half of the support.
  float filter_width = 1.0f;
  float exposure = 1.0f;  // pixel colours are multiplied by it (Cycles' film exposure)
};

// Spectral rendering (integrators/spectral_path.h): paths carry `spectral_samples` wavelengths
// instead of RGB, so glass with an Abbe number disperses light. Radiosity stays RGB.
struct SpectralParams {
  bool spectral = false;
  int spectral_samples = 4;  // wavelengths per path, 1..kSpectrumSamples
};

struct PerformanceParams {
  int threads = 0;  // 0 = all cores
  int tile_size = 64;
};

const ParamSchema<SamplingParams>& sampling_schema();
const ParamSchema<FilmParams>& film_schema();
const ParamSchema<PerformanceParams>& performance_schema();
const ParamSchema<SpectralParams>& spectral_schema();

}  // namespace photon

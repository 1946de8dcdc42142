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
};

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

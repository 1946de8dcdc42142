// Parameters of photon mapping (Jensen 2001), declared once in their schema
// (photon_map_params.cpp).
#pragma once

#include <cstdint>

#include "photon/base/param_schema.h"

namespace photon {

struct PhotonMapParams {
  uint64_t photons = 200000;          // photon paths emitted for the global map
  uint64_t caustic_photons = 100000;  // photon paths aimed at specular objects
  int gather_count = 100;             // k nearest photons in a global-map estimate
  float gather_radius = 0.0f;         // maximum search radius; 0 = from the scene's size
  int caustic_gather_count = 50;      // k nearest photons in a caustic estimate
  int final_gather_rays = 16;         // per camera sample; 0 = read the global map directly
  float photon_time = 0.0f;           // > 0: trace photons for this many seconds instead
  bool irradiance_cache = true;       // final gathers at camera-visible points interpolated
  // Photon counts are scaled down when the photon maps' estimated peak memory would exceed this
  // fraction of the memory available when tracing starts (MemAvailable; photon_memory.h).
  float memory_limit = 0.75f;
};

const ParamSchema<PhotonMapParams>& photon_map_schema();

}  // namespace photon

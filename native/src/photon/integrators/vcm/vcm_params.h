// Parameters of vertex connection and merging (Georgiev et al. 2012), declared once in their
// schema (vcm_params.cpp). They mirror SPPM's (iterations, light paths per iteration, a merging
// radius that shrinks), so the two compare at one budget when set alike.
#pragma once

#include <cstdint>

#include "photon/base/param_schema.h"

namespace photon {

// Which strategies VCM combines: all of them, vertex connections only (bidirectional path
// tracing) or vertex merging only (progressive photon mapping).
enum class VcmMode : uint8_t { kVcm, kBpt, kPpm };

struct VcmParams {
  int vcm_iterations = 64;            // light and camera passes
  uint64_t vcm_light_paths = 100000;  // light subpaths traced per iteration
  float vcm_initial_radius = 0.0f;    // merging radius of the first iteration; 0 = automatic
  float vcm_alpha = 2.0f / 3.0f;      // radius shrinking, r_i = r_1 i^((alpha - 1) / 2)
  float vcm_time = 0.0f;              // > 0: stop after this many seconds
  VcmMode vcm_mode = VcmMode::kVcm;
};

const ParamSchema<VcmParams>& vcm_schema();

}  // namespace photon

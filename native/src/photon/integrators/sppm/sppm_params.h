// Parameters of stochastic progressive photon mapping (Hachisuka & Jensen 2009), declared once
// in their schema (sppm_params.cpp).
#pragma once

#include <cstdint>

#include "photon/base/param_schema.h"

namespace photon {

struct SppmParams {
  int sppm_iterations = 64;                      // camera + photon passes
  uint64_t sppm_photons_per_iteration = 100000;  // photon paths emitted per iteration
  float sppm_initial_radius = 0.0f;              // 0 = a few pixels' footprint per pixel
  float sppm_alpha = 2.0f / 3.0f;                // share of new photons kept (eq. 6 of the paper)
  float sppm_time = 0.0f;                        // > 0: stop after this many seconds
};

const ParamSchema<SppmParams>& sppm_schema();

}  // namespace photon

// Parameters of the stochastic radiosity solve (radiosity_solver.h), declared once in their
// schema (radiosity_params.cpp).
#pragma once

#include <cstdint>

#include "photon/base/param_schema.h"

namespace photon {

// Hard bounds of the schema that the solver (radiosity_solver.cpp) also keeps to when called
// directly.
constexpr double kMinRadiosityThreshold = 1e-4, kMaxRadiosityThreshold = 1.0;
constexpr int kMaxRadiosityIterations = 100;

struct RadiosityParams {
  float radiosity_patch_size = 0.0f;  // element edge length; 0 = automatic (~20k elements)
  uint64_t radiosity_rays = 8000000;  // rays traced by the whole solve
  float radiosity_threshold = 0.01f;  // shooting stops below this unshot fraction
  int radiosity_iterations = 4;       // averaged Jacobi iterations after shooting
};

const ParamSchema<RadiosityParams>& radiosity_schema();

}  // namespace photon

// Statistics of an iterative render (SPPM, VCM), for the UI and logs.
#pragma once

#include <cstddef>
#include <cstdint>

namespace photon {

// What the iterations of a render did; iterations is 0 for integrators that do not iterate.
// photons_emitted: photons (SPPM) or light subpaths (VCM) over all iterations, photons_recorded
// the photons or light vertices stored by the last iteration.
struct IterationStats {
  int iterations = 0;
  uint64_t photons_emitted = 0;
  size_t photons_recorded = 0;   // in the last iteration
  size_t peak_photon_bytes = 0;  // largest photon store (points and search structure) of one
  uint64_t rays = 0;             // photon rays
  uint64_t non_finite = 0;       // camera samples dropped for a NaN / inf value
  double photon_seconds = 0.0, camera_seconds = 0.0;
};

}  // namespace photon

// Statistics of an iterative render (SPPM, VCM), for the UI and logs.
#pragma once

#include <cstddef>
#include <cstdint>

namespace photon {

// photons_emitted: photons (SPPM) or light subpaths (VCM) over all iterations.
struct SppmStats {
  int iterations = 0;
  uint64_t photons_emitted = 0;
  size_t photons_recorded = 0;   // in the last iteration
  size_t peak_photon_bytes = 0;  // largest kd-tree (photons and axes) of an iteration
  uint64_t rays = 0;             // photon rays
  uint64_t non_finite = 0;       // camera samples dropped for a NaN / inf value
  double photon_seconds = 0.0, camera_seconds = 0.0;
};

}  // namespace photon

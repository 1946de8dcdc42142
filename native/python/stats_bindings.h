// Render and bake statistics as Python objects with read-only attributes (the integrator's
// PrepareStats groups are None when their stage did not run).
#pragma once

#include <pybind11/pybind11.h>

#include "photon/integrators/prepare_stats.h"
#include "photon/session/bake.h"

namespace photon_python {

// A bake's timings and its integrator's PrepareStats (BakeResult without the per-point data).
struct BakeStats {
  double build_seconds = 0.0, prepare_seconds = 0.0, bake_seconds = 0.0;
  double locate_seconds = 0.0, share_seconds = 0.0;
  int threads = 0;
  photon::PrepareStats integrator;
};
BakeStats bake_stats(const photon::BakeResult& result);

// PhotonMapStats, PhotonMemoryStats, IrradianceCacheStats, RadiosityStats, PrepareStats,
// RenderStats and BakeStats.
void register_stats_classes(pybind11::module_& m);

}  // namespace photon_python

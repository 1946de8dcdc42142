// The first pass of photon mapping (Jensen 2001 ch. 5): photons leave the
// lights and are traced through the scene with Russian roulette on the material's lobes
// (Jensen 2001 sec. 5.2), stored at every diffuse hit. Photons are traced in parallel in fixed
// chunks whose results are concatenated in chunk order, and every random number comes from
// (seed, pass, photon index), so the maps do not depend on the number of threads.
#pragma once

#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/photon_map/photon_map.h"
#include "photon/integrators/photon_map/photon_sources.h"

namespace photon {

// A point where reflected radiance is precomputed for final gathering (Christensen 1999,
// "Faster Photon Map Global Illumination"): a subset of the global photons' surface points.
struct GatherPoint {
  Vec3 p;
  Vec3 n;  // surface normal on the side the photon arrived from
};

struct PhotonTraceSettings {
  uint64_t global_photons = 200000;  // photon paths to emit (ignored when time_budget > 0)
  uint64_t caustic_photons = 100000;
  double time_budget = 0.0;  // seconds; > 0 traces until the time is spent
  uint64_t seed = 0;
  int max_bounces = 64;         // safety limit; Russian roulette ends paths before
  int gather_point_stride = 4;  // every n-th global photon (by hash) becomes a GatherPoint
  // Each photon carries one wavelength (stratified over the photons, visible-response density)
  // and the maps hold spectral photons (Photon::make_spectral).
  bool spectral = false;
};

struct PhotonTraceResult {
  std::vector<Photon> global;   // every diffuse hit of global photons
  std::vector<Photon> caustic;  // light -> specular+ -> diffuse hits of caustic photons
  std::vector<GatherPoint> gather_points;
  uint64_t global_emitted = 0, caustic_emitted = 0;
  uint64_t rays = 0;
  double seconds = 0.0;
  bool stopped_early = false;  // Esc or the time budget ended tracing before the counts
  bool spectral = false;       // the photons are spectral ones
};

PhotonTraceResult trace_photons(const RenderContext& context, const PhotonSources& sources,
                                const PhotonTraceSettings& settings, const PrepareControl& control);

}  // namespace photon

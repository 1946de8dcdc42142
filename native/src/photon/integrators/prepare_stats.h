// What an integrator's preparation (photon tracing, caches, the radiosity solve) did, as typed
// fields filled by the integrator that ran; a group is empty (std::nullopt) when its stage did
// not run. The render and bake sessions carry it to Python (attributes, native/python).
#pragma once

#include <cstdint>
#include <optional>

namespace photon {

// Jensen's photon maps (photon_map_integrator.h).
struct PhotonMapStats {
  uint64_t photons_emitted = 0;  // global photons
  uint64_t caustic_photons_emitted = 0;
  uint64_t global_photons_stored = 0;
  uint64_t caustic_photons_stored = 0;
  uint64_t radiance_points = 0;  // precomputed radiance records (Christensen 1999)
  uint64_t photon_rays = 0;
  uint64_t photon_map_bytes = 0;  // both maps and the radiance records
  double radiance_cell_size = 0.0;
  double global_gather_radius = 0.0;
  double caustic_gather_radius = 0.0;
  double photon_trace_seconds = 0.0;
  double photon_map_build_seconds = 0.0;
  double radiance_precompute_seconds = 0.0;
};

// The memory plan for the photon counts (a pilot trace): set when it ran.
struct PhotonMemoryStats {
  double estimate_bytes = 0.0;  // planned peak
  double available_bytes = 0.0;
};

// An irradiance cache of final gathers (Ward 1988): at camera-visible points, or among a bake's
// points.
struct IrradianceCacheStats {
  uint64_t records = 0;
  uint64_t candidates = 0;
  uint64_t gather_rays = 0;  // 0 for a bake's cache (not counted there)
  uint64_t bytes = 0;        // 0 for a bake's cache (not counted there)
  double seconds = 0.0;
};

// Stochastic radiosity (radiosity_integrator.h).
struct RadiosityStats {
  uint64_t elements = 0;
  uint64_t patches = 0;
  uint64_t clusters = 0;
  uint64_t split_patches = 0;
  uint64_t first_patches = 0;  // before refinement
  uint64_t vertices = 0;
  double patch_size = 0.0;
  double area = 0.0;
  uint64_t rays = 0;
  double rays_per_second = 0.0;
  uint64_t shooting_iterations = 0;
  uint64_t averaged_iterations = 0;
  double emitted_power = 0.0;  // W
  double absorbed_power = 0.0;
  double absorbed_specular_power = 0.0;
  double escaped_power = 0.0;
  double unshot_power = 0.0;
  double mesh_seconds = 0.0;
  double solve_seconds = 0.0;
  double field_seconds = 0.0;
};

struct PrepareStats {
  std::optional<PhotonMapStats> photon_map;
  std::optional<PhotonMemoryStats> photon_memory;
  std::optional<IrradianceCacheStats> irradiance_cache;       // camera-visible points
  std::optional<IrradianceCacheStats> bake_irradiance_cache;  // among a bake's points
  std::optional<RadiosityStats> radiosity;
};

}  // namespace photon

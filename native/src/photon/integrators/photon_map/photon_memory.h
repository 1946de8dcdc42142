// Peak memory of the photon-mapping preparation, estimated before tracing from a small pilot
// trace, and the photon counts that fit a memory budget (a fraction of the machine's available
// memory). The estimate follows the data structures' sizes through the phases of
// PhotonMapIntegrator::prepare (photon_map_integrator.cpp); photon_memory_test.cpp checks it
// against sizeof, and the report in the README compares it with measured peak RSS.
#pragma once

#include <cstdint>
#include <string>

namespace photon {

struct PhotonMemoryRequest {
  uint64_t global_photons = 0;  // photon paths to emit
  uint64_t caustic_photons = 0;
  // Measured by a pilot trace: photons stored and gather points made per photon emitted.
  double global_stored_per_emitted = 0.0;
  double caustic_stored_per_emitted = 0.0;
  double gather_points_per_emitted = 0.0;  // gather points of the global pass
  bool radiance_records = true;    // final gathering: radiance precomputed at the gather points
  uint64_t irradiance_pixels = 0;  // frame pixels when the irradiance cache is built, else 0
};

// Estimated peak bytes of the preparation for the request's counts.
double photon_peak_bytes(const PhotonMemoryRequest& request);

struct PhotonMemoryPlan {
  uint64_t global_photons = 0, caustic_photons = 0;  // counts to trace
  double requested_bytes = 0.0;                      // estimated peak for the requested counts
  double planned_bytes = 0.0;                        // estimated peak for the planned counts
  double scale = 1.0;  // planned / requested counts (1 when the request fits)
};

// The request's counts, scaled down together (keeping their ratio) when the estimated peak
// exceeds `budget_bytes`. A budget of 0 (unknown) leaves the counts unchanged.
PhotonMemoryPlan plan_photon_memory(const PhotonMemoryRequest& request, double budget_bytes);

// How many of `requested` items of `bytes_each` fit `budget_bytes`: all when they fit, else as
// many as fit but at least one. An unknown budget or size (0) leaves the request unchanged.
uint64_t count_that_fits(uint64_t requested, double bytes_each, double budget_bytes);

// MemAvailable of /proc/meminfo in bytes (the kernel's estimate of memory available to a new
// program without swapping); 0 when it cannot be read.
uint64_t available_memory_bytes();
// MemAvailable parsed from the text of /proc/meminfo; 0 if absent.
uint64_t parse_mem_available(const std::string& meminfo);

// "1.23 GB", "456 MB" for warnings.
std::string bytes_text(double bytes);

}  // namespace photon

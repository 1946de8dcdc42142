#include "photon/integrators/photon_map/photon_memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "photon/integrators/photon_map/irradiance_cache.h"
#include "photon/integrators/photon_map/photon_map.h"
#include "photon/integrators/photon_map/photon_tracer.h"
#include "photon/integrators/photon_map/radiance_cache.h"

namespace photon {
namespace {

// Irradiance-cache records per frame pixel, at most: one candidate per pixel of the 32, 16, 8,
// 4 and 2 px grids (1/1024 + ... + 1/4 < 1/3 per pixel), each usually one record.
constexpr double kIrradianceRecordsPerPixel = 1.0 / 3.0;
// A record is held twice while a level's cache is rebuilt (the list of all records and the
// cache's copy), plus its index and about one BVH node per two records.
constexpr double kIrradianceRecordBytes = 2.0 * sizeof(IrradianceRecord) + sizeof(uint32_t) + 16.0;

}  // namespace

double photon_peak_bytes(const PhotonMemoryRequest& r) {
  const double global_stored = r.global_stored_per_emitted * static_cast<double>(r.global_photons);
  const double caustic_stored =
      r.caustic_stored_per_emitted * static_cast<double>(r.caustic_photons);
  const double gather_points = r.gather_points_per_emitted * static_cast<double>(r.global_photons);
  // Tracing and the kd-tree build hold the photons (stored exactly, no spare capacity) and the
  // gather points.
  const double maps = sizeof(Photon) * (global_stored + caustic_stored);
  const double traced = maps + sizeof(GatherPoint) * gather_points;
  double peak = traced;
  if (r.radiance_records) {
    // Building the radiance cache: the computed records, the sort keys (cell key and index),
    // the reordered copy of the records and the hash table (at most 2 slots per record, the
    // table size rounded up to a power of two: 1-2 slots per record on average, counted as 2).
    constexpr double kSlotBytes = 16.0;
    const double cache_build =
        gather_points *
        (2.0 * sizeof(RadianceRecord) + sizeof(std::pair<uint64_t, uint32_t>) + 2.0 * kSlotBytes);
    peak = std::max(peak, traced + cache_build);
    // The irradiance cache is built while the photons, gather points and radiance cache live.
    const double radiance_cache = gather_points * (sizeof(RadianceRecord) + 2.0 * kSlotBytes);
    const double irradiance = static_cast<double>(r.irradiance_pixels) *
                              kIrradianceRecordsPerPixel * kIrradianceRecordBytes;
    peak = std::max(peak, traced + radiance_cache + irradiance);
  }
  return peak;
}

PhotonMemoryPlan plan_photon_memory(const PhotonMemoryRequest& request, double budget_bytes) {
  PhotonMemoryPlan plan;
  plan.global_photons = request.global_photons;
  plan.caustic_photons = request.caustic_photons;
  plan.requested_bytes = plan.planned_bytes = photon_peak_bytes(request);
  if (!(budget_bytes > 0.0) || plan.requested_bytes <= budget_bytes) return plan;
  // The peak grows with the counts (the largest of a few phases, each affine in them): the
  // largest scale that fits, by bisection.
  auto scaled_request = [&](double scale) {
    PhotonMemoryRequest scaled = request;
    scaled.global_photons =
        static_cast<uint64_t>(std::floor(static_cast<double>(request.global_photons) * scale));
    scaled.caustic_photons =
        static_cast<uint64_t>(std::floor(static_cast<double>(request.caustic_photons) * scale));
    return scaled;
  };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (photon_peak_bytes(scaled_request(mid)) <= budget_bytes ? lo : hi) = mid;
  }
  const double scale = lo;
  const PhotonMemoryRequest scaled = scaled_request(scale);
  plan.global_photons = scaled.global_photons;
  plan.caustic_photons = scaled.caustic_photons;
  plan.planned_bytes = photon_peak_bytes(scaled);
  plan.scale = scale;
  return plan;
}

uint64_t parse_mem_available(const std::string& meminfo) {
  std::istringstream in(meminfo);
  std::string line;
  while (std::getline(in, line)) {
    unsigned long long kb = 0;
    if (std::sscanf(line.c_str(), "MemAvailable: %llu kB", &kb) == 1) return kb * 1024ull;
  }
  return 0;
}

uint64_t count_that_fits(uint64_t requested, double bytes_each, double budget_bytes) {
  if (!(budget_bytes > 0.0) || !(bytes_each > 0.0)) return requested;
  const double fit = std::floor(budget_bytes / bytes_each);
  return fit >= static_cast<double>(requested) ? requested
                                               : std::max<uint64_t>(1, static_cast<uint64_t>(fit));
}

uint64_t available_memory_bytes() {
  std::ifstream file("/proc/meminfo");
  if (!file) return 0;
  std::stringstream text;
  text << file.rdbuf();
  return parse_mem_available(text.str());
}

std::string bytes_text(double bytes) {
  char buf[32];
  if (bytes >= 1e9)
    std::snprintf(buf, sizeof buf, "%.2f GB", bytes / 1e9);
  else
    std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  return buf;
}

}  // namespace photon

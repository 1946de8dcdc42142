#include "photon/integrators/photon_map/irradiance_cache_points.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>

#include "photon/base/rng.h"

namespace photon {
namespace {

constexpr uint64_t kPointCacheStreamTag = 0xBA4EC4C3Eull;  // separates record samplers

// One of six directions (dominant axis and its sign), so the two sides of a thin wall, or
// faces meeting at a corner, get their own candidates in a cell.
uint64_t normal_bin(const Vec3& n) {
  const float ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  if (ax >= ay && ax >= az) return n.x >= 0.0f ? 0 : 1;
  if (ay >= az) return n.y >= 0.0f ? 2 : 3;
  return n.z >= 0.0f ? 4 : 5;
}

struct KeyedPoint {
  uint64_t key;
  uint32_t index;
  bool operator<(const KeyedPoint& o) const { return key != o.key ? key < o.key : index < o.index; }
};

}  // namespace

IrradianceCache build_point_irradiance_cache(
    const BakePointSet& points,
    const std::function<Vec3(const SurfaceInteraction& si, int rays, Sampler& sampler,
                             float* harmonic_distance)>& gather,
    const PointIrradianceCacheSettings& settings, const PrepareControl& control,
    PointIrradianceCacheStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const float a = settings.accuracy;
  IrradianceCache cache({}, a);
  const size_t count = points.count;
  const Vec3* positions = points.positions;
  const Vec3* normals = points.normals;
  const uint8_t* valid = points.valid;
  // Candidate pool: every k-th valid point.
  std::vector<uint32_t> pool;
  for (size_t i = 0; i < count; ++i)
    if ((!valid || valid[i]) && is_finite(positions[i])) pool.push_back(static_cast<uint32_t>(i));
  if (pool.empty() || settings.rays <= 0) return cache;
  if (pool.size() > settings.max_candidates) {
    const size_t step = (pool.size() + settings.max_candidates - 1) / settings.max_candidates;
    size_t kept = 0;
    for (size_t j = 0; j < pool.size(); j += step) pool[kept++] = pool[j];
    pool.resize(kept);
  }
  Vec3 lo(INFINITY), hi(-INFINITY);
  for (uint32_t i : pool) lo = min(lo, positions[i]), hi = max(hi, positions[i]);
  // Only a floor for coincident points: a scene of any scale keeps its own diagonal.
  float diagonal = length(hi - lo);
  if (!(diagonal > 0.0f)) diagonal = 1e-6f;
  const float finest_cell = diagonal / static_cast<float>(std::max(settings.finest_divisions, 1));
  const float min_reach = settings.min_cells * finest_cell;
  const float max_reach = std::max(settings.max_fraction * diagonal, min_reach);

  std::vector<IrradianceRecord> all;
  std::atomic<uint64_t> candidates{0};
  int levels = 0;
  for (int d = settings.coarsest_divisions; d <= settings.finest_divisions; d *= 2) ++levels;
  int level = 0;
  std::vector<KeyedPoint> keyed(pool.size());
  for (int divisions = std::max(settings.coarsest_divisions, 1);
       divisions <= settings.finest_divisions; divisions *= 2, ++level) {
    const float inv_cell = static_cast<float>(divisions) / diagonal;
    // 20 bits per axis are plenty for 256 divisions (the cell index is < divisions + 1).
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pool.size(), 4096), [&](const auto& r) {
      for (size_t j = r.begin(); j != r.end(); ++j) {
        const Vec3 c = (positions[pool[j]] - lo) * inv_cell;
        const uint64_t x = static_cast<uint64_t>(c.x), y = static_cast<uint64_t>(c.y),
                       z = static_cast<uint64_t>(c.z);
        keyed[j].key = (((x << 20 | y) << 20 | z) << 3) | normal_bin(normals[pool[j]]);
        keyed[j].index = pool[j];
      }
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());
    std::vector<uint32_t> level_candidates;
    for (size_t j = 0; j < keyed.size(); ++j)
      if (j == 0 || keyed[j].key != keyed[j - 1].key) level_candidates.push_back(keyed[j].index);
    std::sort(level_candidates.begin(), level_candidates.end());
    candidates += level_candidates.size();

    std::vector<IrradianceRecord> found(level_candidates.size());
    std::vector<uint8_t> made(level_candidates.size(), 0);
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, level_candidates.size(), 4), [&](const auto& r) {
          for (size_t j = r.begin(); j != r.end(); ++j) {
            if (control.cancelled()) return;
            const uint32_t i = level_candidates[j];
            if (cache.covers(positions[i], normals[i], settings.coverage * a)) continue;
            SurfaceInteraction si;
            if (!points.interaction(i, &si)) continue;
            Sampler sampler(settings.seed,
                            hash_combine(kPointCacheStreamTag, uint64_t{i} * 16 + level), 0);
            float harmonic = INFINITY;
            const Vec3 value = gather(si, settings.rays, sampler, &harmonic);
            IrradianceRecord record;
            record.p = positions[i];
            record.n = normals[i];
            record.value = value;
            record.radius = std::clamp(harmonic, min_reach / a, max_reach / a);
            if (std::isfinite(record.radius) && record.radius > 0.0f && is_finite(value)) {
              found[j] = record;
              made[j] = 1;
            }
          }
        });
    if (control.cancelled()) return IrradianceCache({}, a);
    for (size_t j = 0; j < found.size(); ++j)
      if (made[j]) all.push_back(found[j]);
    cache = IrradianceCache(all, a);
    control.report("Irradiance cache: " + std::to_string(cache.size()) + " records",
                   static_cast<float>(level + 1) / std::max(levels, 1));
  }
  if (stats) {
    stats->candidates = candidates.load();
    stats->gather_rays = static_cast<uint64_t>(cache.size()) * settings.rays;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return cache;
}

}  // namespace photon

// Irradiance-cache records (irradiance_cache.h) placed among a given set of surface points, for
// lighting bakes: a bake shades millions of points (face corners, lightmap texels) whose
// indirect light varies slowly, so the expensive final gather is computed at sparse records
// and interpolated (Ward, Rubinstein & Clear 1988) instead of at every point.
//
// Placement mirrors irradiance_cache_build.h with world-space grids instead of pixel grids: on
// coarse-to-fine grids (cell sizes diagonal / 16 ... diagonal / 256 of the points' bounding
// box), the lowest-index point of each (cell, normal direction) is a candidate; every candidate
// of a level not covered by the records of the earlier levels (Ward's eps < coverage * a) makes
// a record, in parallel. Records have their own seeded samplers, so the cache does not depend
// on the thread count. Candidates come from at most `max_candidates` points (every k-th), which
// bounds the placement cost for huge point sets (lightmaps).
//
// A record's radius is the harmonic mean distance of its gather rays, clamped so that its
// domain a R_i spans between min_cells finest cells and max_fraction of the diagonal: no tiny
// records in corners, no records smearing uneven light over a large part of the scene (the
// cache has no gradients; see irradiance_cache_build.h).
#pragma once

#include <functional>

#include "photon/integrators/photon_map/irradiance_cache_build.h"

namespace photon {

struct PointIrradianceCacheSettings {
  float accuracy = 0.25f;       // Ward's a
  float coverage = 0.5f;        // placement threshold, as IrradianceCacheSettings::coverage
  int rays = 1024;              // final-gather rays per record
  int coarsest_divisions = 16;  // grid cell = diagonal / divisions, doubled each level
  int finest_divisions = 256;
  float min_cells = 3.0f;             // a R_i >= min_cells * finest cell
  float max_fraction = 1.0f / 32.0f;  // a R_i <= max_fraction * diagonal
  size_t max_candidates = 400000;
  uint64_t seed = 0;
};

struct PointIrradianceCacheStats {
  uint64_t candidates = 0;
  uint64_t gather_rays = 0;
  double seconds = 0.0;
};

// `gather` computes a record's value (reflected radiance for albedo 1) at an interaction.
// Returns an empty cache when cancelled.
IrradianceCache build_point_irradiance_cache(
    const BakePointSet& points,
    const std::function<Vec3(const SurfaceInteraction& si, int rays, Sampler& sampler,
                             float* harmonic_distance)>& gather,
    const PointIrradianceCacheSettings& settings, const PrepareControl& control,
    PointIrradianceCacheStats* stats);

}  // namespace photon

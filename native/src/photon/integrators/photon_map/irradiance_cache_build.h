// Places irradiance-cache records (irradiance_cache.h) before rendering, so the image does not
// depend on the order in which threads render tiles.
//
// Candidates are the diffuse points that camera rays through pixel centres see, directly or
// through chains of perfectly specular reflection and refraction, on coarse-to-fine grids of
// pixels (32, 16, 8, 4, 2 px apart). The first level makes a record at every candidate; each
// later level makes one, in parallel, only where the records of the earlier levels do not
// cover the candidate (Ward's eps < a). Coverage is tested against earlier levels only, and
// every record has its own seeded sampler, so the cache is the same for any thread count.
//
// A record's radius is the harmonic mean distance of its gather rays (Ward 1988), clamped so
// that its domain, a R_i, spans between `min_pixels` and `max_pixels` pixels at the record's
// distance from the camera (Tabellion & Lamorlette 2004, sec. 3.3): no tiny records in corners,
// no records spreading over detail that the screen resolves. Ward & Heckbert's gradients are
// not used: the guided, R2-stratified gather has no hemisphere grid to derive them from.
//
// The whole frame is covered even when a render border is set, so a border render equals the
// same region of the full render.
#pragma once

#include <functional>

#include "photon/integrators/camera_path.h"
#include "photon/integrators/integrator.h"
#include "photon/integrators/photon_map/irradiance_cache.h"

namespace photon {

class Bsdf;

struct IrradianceCacheSettings {
  float accuracy = 0.25f;  // Ward's a
  // A candidate is covered when an earlier record has eps < coverage * a: below 1, records
  // overlap more, so each lookup averages several and their noise does not show as blotches.
  float coverage = 0.5f;
  int rays = 1024;  // final-gather rays per record
  // a R_i clamped to [min_pixels, max_pixels] pixels. The upper clamp matters most: Ward's
  // radius ignores gradients from uneven lighting (a ceiling lit by the bright floor patch
  // below the lamp), which records spanning 10-20 px smear by 5-10% without gradients.
  float min_pixels = 1.5f;
  float max_pixels = 5.0f;
  int coarsest_spacing = 32;  // pixels between the first level's candidates
  int finest_spacing = 2;     // halved each level down to this
};

// The final gather at a record: reflected radiance for albedo 1 from `rays` rays, and the
// harmonic mean of their hit distances (infinity when every ray escapes).
using RecordGather = std::function<Vec3(const SurfaceInteraction& si, const Bsdf& bsdf, int rays,
                                        Sampler& sampler, float* harmonic_distance)>;

struct IrradianceCacheBuildStats {
  uint64_t candidates = 0;  // diffuse points tested
  uint64_t gather_rays = 0;
  double seconds = 0.0;
};

// Calls `candidate` at every diffuse point (non-black diffuse albedo) where a camera path along
// `camera_ray` final-gathers: the camera walk itself (walk_camera_path with
// cache_placement_walk(), camera_path.h), not a copy of it. `path_sampler` chooses between delta
// lobes (glass reflects or refracts).
void visit_cache_candidates(const RenderContext& context, const Ray& camera_ray,
                            Sampler& path_sampler,
                            const std::function<void(const PathVertex&)>& candidate);

// Builds the cache for the context's camera and frame. Returns an empty cache when cancelled.
IrradianceCache build_irradiance_cache(const RenderContext& context,
                                       const IrradianceCacheSettings& settings,
                                       const RecordGather& gather, const PrepareControl& control,
                                       IrradianceCacheBuildStats* stats);

}  // namespace photon

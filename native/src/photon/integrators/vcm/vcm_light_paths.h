// VCM's light subpaths of one iteration (Georgiev et al. 2012 sec. 5; Davidovic et al. 2012,
// the light-subpath half of the recursive MIS quantities): each starts on an emitter picked by
// power, stores a vertex at every surface with a connectible BSDF (for connections and
// merging), and in the modes with connections connects each such vertex to the camera (light
// tracing), recorded as a splat.
//
// Determinism: subpath i draws from the (seed, iteration, i) stream; subpaths are traced in
// fixed chunks of indices whose vertices and splats are concatenated in chunk order, and the
// splats are then added to the image one after the other in that order (never by atomics), so
// the iteration's result does not depend on the thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "photon/integrators/vcm/vcm_camera_model.h"
#include "photon/integrators/vcm/vcm_common.h"

namespace photon {

// A light subpath vertex seen by the camera at raster point (x, y). Pixel j whose filter
// covers it receives value f_j / (1 + f_j a) (balance heuristic against the camera-side
// strategies, whose densities relative to light tracing are f_j a).
struct VcmSplat {
  float x = 0.0f, y = 0.0f;
  Vec3 value{0.0f};
  float a = 0.0f;
};

struct VcmLightPass {
  std::vector<VcmLightVertex> vertices;
  std::vector<uint64_t> path_end;  // vertices of subpath i: [path_end[i-1], path_end[i])
  std::vector<VcmSplat> splats;
  uint64_t rays = 0;
  bool cancelled = false;

  size_t path_begin(uint64_t i) const { return i == 0 ? 0 : path_end[i - 1]; }
};

// `colours`: the iteration's wavelengths in spectral mode (vcm_common.h).
VcmLightPass trace_vcm_light_paths(const RenderContext& context, const VcmLights& lights,
                                   const VcmCamera& camera, const VcmMis& mis, uint32_t iteration,
                                   const std::atomic<bool>& cancel,
                                   const VcmColours& colours = VcmColours{});

// Estimated peak bytes of one iteration's light pass for `paths` subpaths storing
// `vertices_per_path` vertices and `splats_per_path` splats on average: the chunks' output and
// the joined pass are alive together while they are joined, then the pass beside the merging
// grid (vcm_grid.h, at most 24 bytes per vertex while it is built).
double vcm_light_pass_peak_bytes(double paths, double vertices_per_path, double splats_per_path);

struct VcmLightPathPlan {
  uint64_t light_paths = 0;      // per iteration, at most the request
  double requested_bytes = 0.0;  // estimated peak of the request (0 when no pilot was needed)
};

// Light subpaths per iteration whose pass fits `budget_bytes` (0 = unknown: the request). When
// the request could exceed it, a pilot of a few thousand subpaths (from an iteration index no
// render reaches) measures the vertices and splats per subpath. The count also stays below the
// merging grid's 2^32 vertices. `mis` is the first iteration's.
VcmLightPathPlan plan_vcm_light_paths(const RenderContext& context, const VcmLights& lights,
                                      const VcmCamera& camera, const VcmMis& mis,
                                      uint64_t requested, double budget_bytes);

// Adds the splats to `image` (RGB per pixel of the region x0, y0 .. x1, y1 of the full frame)
// in order.
void apply_vcm_splats(const std::vector<VcmSplat>& splats, const VcmCamera& camera,
                      const FilmFrame& frame, std::vector<Vec3>* image);

}  // namespace photon

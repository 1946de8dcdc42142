// Follows a ray through perfect mirrors and glass (seed 000 eq. 2.15, the specular part of the
// rendering equation, traced exactly) until it reaches a diffuse surface or leaves the scene.
// Shared by camera paths and final-gather rays.
#pragma once

#include "photon/integrator.h"

namespace photon {

struct DiffuseVertex {
  bool found = false;   // the chain ended on a diffuse surface within the depth limit
  SurfaceInteraction si;  // normals flipped to face the arriving ray
  Vec3 throughput{1.0f};  // product of the specular tints along the chain
  int depth = 0;          // specular bounces before the diffuse surface
  Hit hit;                // the diffuse surface's hit (when found)
  bool escaped = false;   // the chain left the scene (not found, and not stopped by max depth)
};

// `first` (optional) is the already traced first hit of `ray`. When `emitted` is given, light
// met on the way (light surfaces, emissive surfaces, the world and suns) is added to it,
// weighted by the throughput; `alpha` (optional) is set to 1 if the first ray hit anything.
// `mask` is the visibility of the first segment.
DiffuseVertex trace_specular_chain(const RenderContext& context, Ray ray, const CameraHit* first,
                                   uint32_t mask, Sampler& sampler, Vec3* emitted,
                                   float* alpha);

}  // namespace photon

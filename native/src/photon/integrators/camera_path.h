// Follows a camera ray through the non-diffuse lobes of the surfaces it meets (Jensen
// 2001 sec. 9.1: specular and glossy reflection and refraction, ray traced), adding emission met on the
// way and direct light at every vertex (direct_lighting.h). The diffuse lobes' indirect light
// is left to the integrator, through `shade_diffuse`, so ray tracing and photon mapping share
// one path walker.
#pragma once

#include <functional>

#include "photon/integrators/integrator.h"
#include "photon/render/material_eval.h"

namespace photon {

struct PathVertex {
  const SurfaceInteraction* si;  // normals as wound by the mesh
  const ShadingPoint* shading;   // BSDF with normals facing wo
  Vec3 wo;
  Vec3 throughput;  // camera -> this vertex, without the vertex's own BSDF
  int depth = 0;    // bounces before this vertex
  bool after_glossy = false;  // a rough (non-delta) lobe was sampled on the way here
};

using DiffuseShader = std::function<void(const PathVertex& vertex, RadianceSample* result)>;

// Traces the path of one camera sample. `first` is the camera ray's already traced first hit.
// `light_sampled` are the lobes lit by light sampling at every vertex (radiosity leaves out
// the diffuse lobes: its solution already holds their direct light).
void trace_camera_path(const RenderContext& context, const Ray& camera_ray,
                       const CameraHit& first, Sampler& sampler, const DiffuseShader& shade_diffuse,
                       RadianceSample* result, uint8_t light_sampled = kLobeDiffuse | kLobeGlossy);

// The ray visibility class of the next segment after a sampled lobe (Cycles' ray types).
uint32_t visibility_after(uint8_t lobe_flags);

// Shading of `si` as seen along -ray_direction, with the context's textures.
inline ShadingPoint shade(const RenderContext& context, const SurfaceInteraction& si,
                          const Vec3& wo) {
  return shade_surface(si, wo, *context.accel, context.textures);
}

}  // namespace photon

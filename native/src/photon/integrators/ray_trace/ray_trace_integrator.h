// Whitted-style ray tracing (Whitted 1980) extended to glossy lobes: direct light at every
// surface, mirror, glossy and glass lobes followed up to max_depth (camera_path.h), no indirect
// diffuse light.
#pragma once

#include "photon/integrators/pixel_integrator.h"
#include "photon/integrators/registry.h"

namespace photon {

class RayTraceIntegrator : public PixelIntegrator {
 public:
  RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                   const CameraHit& first, Sampler& sampler) const override;
};

IntegratorInfo ray_trace_integrator_info();

}  // namespace photon

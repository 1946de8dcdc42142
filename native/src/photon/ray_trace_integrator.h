// Whitted-style ray tracing (Whitted 1980): direct light from every light at diffuse surfaces,
// perfect mirror reflection and dielectric refraction followed recursively up to max_depth.
#pragma once

#include "photon/integrator.h"

namespace photon {

class RayTraceIntegrator : public Integrator {
 public:
  RadianceSample radiance_from_hit(const RenderContext& context, const Ray& camera_ray,
                                   const CameraHit& first, Sampler& sampler) const override;
};

}  // namespace photon

#include "photon/integrators/ray_trace/ray_trace_integrator.h"

#include "photon/integrators/camera_path.h"

namespace photon {

// Whitted-style ray tracing with glossy lobes: direct light at every surface, specular and
// glossy paths traced, no indirect diffuse light.
RadianceSample RayTraceIntegrator::radiance_from_hit(const RenderContext& context,
                                                     const Ray& camera_ray,
                                                     const CameraHit& first,
                                                     Sampler& sampler) const {
  RadianceSample result;
  trace_camera_path(context, camera_ray, first, sampler,
                    [](const PathVertex&, RadianceSample*) {}, &result);
  return result;
}

}  // namespace photon

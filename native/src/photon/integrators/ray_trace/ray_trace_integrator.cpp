#include "photon/integrators/ray_trace/ray_trace_integrator.h"

#include "photon/integrators/camera_path.h"

namespace photon {

// Whitted-style ray tracing with glossy lobes: direct light at every surface, specular and
// glossy paths traced, no indirect diffuse light.
RadianceSample RayTraceIntegrator::radiance_from_hit(const RenderContext& context,
                                                     const Ray& camera_ray, const CameraHit& first,
                                                     Sampler& sampler) const {
  RadianceSample result;
  trace_camera_path(
      context, camera_ray, first, sampler, [](const PathVertex&, RadianceSample*) {}, &result);
  return result;
}

IntegratorInfo ray_trace_integrator_info() {
  IntegratorInfo info;
  info.type = IntegratorType::kRayTrace;
  info.label = "Ray Tracing";
  info.description = "Whitted ray tracing: direct light, perfect mirrors and glass";
  info.capabilities.name = "RAY_TRACE";
  info.capabilities.no_bake_reason =
      "the RAY_TRACE integrator has no view-independent lighting solution to bake; bake from "
      "the photon maps or the radiosity solution";
  info.make = [] { return std::unique_ptr<Integrator>(new RayTraceIntegrator); };
  return info;
}

}  // namespace photon

#include "photon/ray_trace_integrator.h"

#include "photon/direct_lighting.h"
#include "photon/specular_chain.h"

namespace photon {

RadianceSample RayTraceIntegrator::radiance_from_hit(const RenderContext& context,
                                                     const Ray& camera_ray,
                                                     const CameraHit& first,
                                                     Sampler& sampler) const {
  RadianceSample result;
  const DiffuseVertex v = trace_specular_chain(context, camera_ray, &first, kVisibleCamera,
                                               sampler, &result.direct, &result.alpha);
  if (v.found && !is_black(v.si.mat->color))
    result.direct += v.throughput * v.si.mat->color * kInvPi *
                     direct_irradiance(context, v.si, sampler);
  return result;
}

}  // namespace photon

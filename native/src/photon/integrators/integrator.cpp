#include "photon/integrators/integrator.h"

#include "photon/integrators/photon_map/photon_map_integrator.h"
#include "photon/integrators/radiosity/radiosity_integrator.h"
#include "photon/integrators/ray_trace/ray_trace_integrator.h"

namespace photon {

std::unique_ptr<Integrator> make_integrator(IntegratorType type) {
  switch (type) {
    case IntegratorType::kRayTrace:
      return std::make_unique<RayTraceIntegrator>();
    case IntegratorType::kPhotonMap:
      return std::make_unique<PhotonMapIntegrator>();
    case IntegratorType::kRadiosity:
      return std::make_unique<RadiosityIntegrator>();
  }
  return std::make_unique<PhotonMapIntegrator>();
}

}  // namespace photon

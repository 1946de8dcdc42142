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
    case IntegratorType::kSppm:
    case IntegratorType::kVcm:
      // SPPM and VCM iterate over the whole frame (integrator_capabilities: iterative); sessions
      // that render per camera sample (the viewport, previews) show its scene with photon mapping,
      // the estimator it refines.
      return std::make_unique<PhotonMapIntegrator>();
  }
  return std::make_unique<PhotonMapIntegrator>();
}

IntegratorCapabilities integrator_capabilities(IntegratorType type) {
  IntegratorCapabilities c;
  switch (type) {
    case IntegratorType::kRayTrace:
      c.name = "RAY_TRACE";
      c.no_bake_reason =
          "the RAY_TRACE integrator has no view-independent lighting solution to bake; "
          "bake from the photon maps or the radiosity solution";
      break;
    case IntegratorType::kPhotonMap:
      c.name = "PHOTON_MAP";
      c.prepares = true;
      c.bake = true;
      c.shares_preparation = true;
      // Only photon tracing (photon_tracer.cpp) polls stop_early; the maps are then built from
      // the photons stored so far.
      c.stop_early = true;
      c.stop_early_status = "Tracing photons";
      c.stop_early_effect = "photon tracing stopped, rendering with the photons traced so far";
      break;
    case IntegratorType::kRadiosity:
      c.name = "RADIOSITY";
      c.prepares = true;
      c.bake = true;
      // The solver (radiosity_solver.cpp, radiosity_refine.cpp) keeps the solution so far.
      c.stop_early = true;
      c.stop_early_effect = "radiosity solve stopped, rendering the solution so far";
      break;
    case IntegratorType::kSppm:
      c.name = "SPPM";
      c.iterative = true;
      c.no_bake_reason =
          "the SPPM integrator converges per pixel of a view and has no view-independent "
          "lighting solution to bake; bake from the photon maps or the radiosity solution";
      break;
    case IntegratorType::kVcm:
      c.name = "VCM";
      c.iterative = true;
      c.no_bake_reason =
          "the VCM integrator converges per pixel of a view and has no view-independent "
          "lighting solution to bake; bake from the photon maps or the radiosity solution";
      break;
  }
  return c;
}

}  // namespace photon

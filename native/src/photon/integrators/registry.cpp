#include "photon/integrators/registry.h"

#include "photon/base/check.h"
#include "photon/integrators/photon_map/photon_map_integrator.h"
#include "photon/integrators/radiosity/radiosity_integrator.h"
#include "photon/integrators/ray_trace/ray_trace_integrator.h"
#include "photon/integrators/sppm/sppm_integrator.h"
#include "photon/integrators/vcm/vcm_integrator.h"

namespace photon {

const std::vector<IntegratorInfo>& integrator_registry() {
  static const std::vector<IntegratorInfo> registry = {
      photon_map_integrator_info(), ray_trace_integrator_info(), radiosity_integrator_info(),
      sppm_integrator_info(),       vcm_integrator_info(),
  };
  // Types are stored in .blend files: two integrators may not share one.
  static const bool unique = [] {
    for (size_t i = 0; i < registry.size(); ++i)
      for (size_t j = i + 1; j < registry.size(); ++j)
        if (registry[i].type == registry[j].type) return false;
    return true;
  }();
  CHECK(unique);
  return registry;
}

const IntegratorInfo& integrator_info(IntegratorType type) {
  const std::vector<IntegratorInfo>& registry = integrator_registry();
  for (const IntegratorInfo& info : registry)
    if (info.type == type) return info;
  return registry.front();
}

std::unique_ptr<Integrator> make_integrator(IntegratorType type) {
  return integrator_info(type).make();
}

IntegratorCapabilities integrator_capabilities(IntegratorType type) {
  return integrator_info(type).capabilities;
}

}  // namespace photon

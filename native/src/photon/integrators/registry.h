// The integrators Photon has, each described once by its own folder (its id, what it can do and
// how to make one): the render settings' enum, the parameter schema, Python and the sessions all
// read this list, so an integrator is added by its folder and one line in registry.cpp.
#pragma once

#include <memory>
#include <vector>

#include "photon/integrators/integrator.h"

namespace photon {

// What an integrator can do, asked of the registry by the sessions and the add-on instead of
// testing for particular integrators.
struct IntegratorCapabilities {
  const char* name = "";  // as Python and the schema name it: "PHOTON_MAP"
  // prepare() does work of its own before the first pixel (photon maps, a radiosity solve).
  bool prepares = false;
  // baked_radiance gives a view-independent solution that lighting bakes read.
  bool bake = false;
  const char* no_bake_reason = "";  // for the user, when bake is false
  // prepare() ends early on PrepareControl::stop_early and the render goes on with what was
  // prepared, while the preparation's status starts with stop_early_status ("" = all of it).
  bool stop_early = false;
  const char* stop_early_status = "";
  const char* stop_early_effect = "";  // for the user: what the render goes on with
  // prepare()'s result can be saved and loaded (save_prepared / load_prepared), so renders of
  // bands of one frame share one preparation.
  bool shares_preparation = false;
  // Renders the whole frame in iterations, refining it after each (SPPM, VCM), instead of
  // tiles that finish one by one.
  bool iterative = false;
  // Renders at sampled wavelengths when the settings ask for it (radiosity stays RGB).
  bool spectral = true;
};

struct IntegratorInfo {
  // Its value in RenderSettings::integrator (stored in .blend files: never reused).
  IntegratorType type = IntegratorType::kPhotonMap;
  const char* label = "";        // for the user: "Photon Mapping"
  const char* description = "";  // one sentence for the user
  IntegratorCapabilities capabilities;
  std::unique_ptr<Integrator> (*make)() = nullptr;
};

// Every integrator, in the order the user sees them (the default first).
const std::vector<IntegratorInfo>& integrator_registry();
// The integrator of `type`; the default one (photon mapping) for a type no integrator has.
const IntegratorInfo& integrator_info(IntegratorType type);

std::unique_ptr<Integrator> make_integrator(IntegratorType type);
IntegratorCapabilities integrator_capabilities(IntegratorType type);

}  // namespace photon

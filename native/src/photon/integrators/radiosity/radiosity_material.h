// Everything the radiosity integrator reads from materials, in one place.
#pragma once

#include "photon/scene/scene.h"

namespace photon {

// Whether a surface may take part in the radiosity solution (gets elements, receives and
// reflects power): materials that can have a diffuse lobe. Pure mirrors, glass and metals only
// redirect rays; what a mixed surface reflects diffusely is read per hit from its BSDF.
inline bool is_radiosity_surface(const Material& m) {
  for (const Closure& c : m.closures) {
    if (c.type == ClosureType::kDiffuse) return true;
    if (c.type == ClosureType::kPrincipled) {
      const Input& metallic = c[Param::kMetallic];
      const Input& transmission = c[Param::kTransmission];
      const bool metal = metallic.is_constant() && metallic.value.x >= 1.0f;
      const bool glass = transmission.is_constant() && transmission.value.x >= 1.0f;
      if (!metal && !glass) return true;
    }
  }
  return false;
}

}  // namespace photon

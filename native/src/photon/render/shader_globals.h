// The ShaderGlobals a shader program reads at a surface point: position, normals, texture
// coordinates, the object's and the camera's transforms, and the ray that arrived.
#pragma once

#include "photon/shading/program.h"

namespace photon {

class Accel;
class TextureSet;
struct SurfaceInteraction;

// The ray that reached a shading point, for the Light Path node (and the Bump node's step). The
// default is a diffusely reflected ray: what photons, gathers and light paths shade with.
struct ShadeRay {
  uint32_t flags = kRayDiffuse | kRayReflect;
  float length = 0.0f;
  uint16_t depth = 0, diffuse_depth = 0, glossy_depth = 0, transparent_depth = 0,
           transmission_depth = 0;
};

// `wo` points away from the surface towards where the ray came from. `accel` (may be null)
// supplies UV tangents.
ShaderGlobals surface_globals(const SurfaceInteraction& si, const Vec3& wo, const Accel* accel,
                              const TextureSet* textures, const ShadeRay& ray);

}  // namespace photon

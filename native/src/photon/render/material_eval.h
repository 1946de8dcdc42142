// Evaluates a Material at a hit point: textures are read, Mix/Add weights multiplied out, and
// each closure becomes BSDF lobes (Cycles 3.4's Principled v1 model for the Principled BSDF).
#pragma once

#include "photon/render/accel.h"
#include "photon/render/bsdf.h"
#include "photon/render/shader_globals.h"
#include "photon/scene/material.h"
#include "photon/shading/textures.h"

namespace photon {

struct ShadingPoint {
  Bsdf bsdf;
  Vec3 emission{0.0f};   // emitted radiance, both sides (as in Cycles)
  float holdout = 0.0f;  // summed weight of Holdout closures, in [0, 1]
};

// The Blender socket name of a param, for warnings ("Base Color").
const char* input_label(ClosureType type, Param p);

// The BSDF and emission of `si` seen from direction `wo` (pointing away from the surface).
// Normals are flipped to wo's side; a normal map bends the shading normal. `textures` may be
// null (inputs then use their constants). `accel` supplies UV tangents for normal maps.
ShadingPoint shade_surface(const SurfaceInteraction& si, const Vec3& wo, const Accel& accel,
                           const TextureSet* textures, const ShadeRay& ray = ShadeRay{});

// The material's AOV outputs at `si` seen along `ray` from `wo`: out[k] for material.aovs[k] (a
// value AOV in .x), as the nodes compute them, unclamped (non-finite values read as 0). Runs the
// program again; only camera hits that write shader AOVs need it.
void eval_material_aovs(const Material& material, const SurfaceInteraction& si, const Vec3& wo,
                        const Accel& accel, const TextureSet* textures, const ShadeRay& ray,
                        Vec3* out);

// Emitted radiance only (for emissive triangles as lights): cheaper than shade_surface.
// `wo` (towards the viewer) matters only to programs that read the incoming direction; without
// it the geometric normal stands in.
Vec3 emitted_radiance(const Material& material, const SurfaceInteraction& si,
                      const TextureSet* textures, const Vec3* wo = nullptr);

}  // namespace photon

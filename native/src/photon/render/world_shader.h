// The world's node tree evaluated for a direction: the Background's colour x strength (of a
// mix of Backgrounds) for the rays that leave the scene, as Cycles' background shader.
#pragma once

#include <cstdint>

#include "photon/base/math.h"
#include "photon/scene/scene.h"
#include "photon/shading/program.h"

namespace photon {

class TextureSet;

// Radiance arriving along `direction` (pointing away from the scene) for a ray of kind
// `ray_flags` (LightPathFlag bits: kRayCamera for camera rays). The constant colour when the
// world has no program; never negative or non-finite, at most the brightest emission.
Vec3 world_radiance(const World& world, const Vec3& direction, uint32_t ray_flags,
                    const TextureSet* textures);

// The world's AOV outputs for a camera ray leaving the scene along `direction`: out[k] for
// world.aovs[k] (a value AOV in .x), unclamped, non-finite values read as 0.
void world_aovs(const World& world, const Vec3& direction, const TextureSet* textures, Vec3* out);

// Ray flags of the rays that light the scene from the world (not camera rays).
constexpr uint32_t kWorldLightingRay = kRayDiffuse | kRayReflect;

}  // namespace photon

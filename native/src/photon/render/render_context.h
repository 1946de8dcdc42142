// What every part of a render reads, shared by all threads: the scene, its BVH and textures, the
// lights and emitters, and the settings. Built once per render (session/scene_resources.h);
// the types it points at live in the layers that own them, so any layer can pass it on.
#pragma once

namespace photon {

class Accel;
class EmissiveMeshes;
class EmitterSet;
class LightSet;
class TextureSet;
struct RenderSettings;
struct Scene;

// Read-only state shared by all threads during a render.
struct RenderContext {
  const Scene* scene = nullptr;
  const Accel* accel = nullptr;
  const LightSet* lights = nullptr;
  const RenderSettings* settings = nullptr;
  const EmissiveMeshes* emissive = nullptr;  // emissive triangles as lights (may be empty)
  const TextureSet* textures = nullptr;      // the scene's image textures (may be null)
  const EmitterSet* emitters = nullptr;      // lamps, emissive triangles and world as emitters
};

}  // namespace photon

// Everything rendering derives from a Scene before the first pixel: the BVH, the lights, the
// image textures, the emissive triangles, and the RenderContext that points at them. Render
// sessions, lighting bakes, tests and benchmarks all build it here, so none of them can forget
// a part (a bake without textures would bake untextured albedo).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/lights/emissive_mesh.h"
#include "photon/lights/emitter_set.h"
#include "photon/lights/lights.h"
#include "photon/render/accel.h"
#include "photon/shading/textures.h"

namespace photon {

// The BVH quality that renders `scene` with `settings` soonest: the fast (LOW) build when the
// render traces too few rays per triangle to repay a MEDIUM build (a small preview of a big
// mesh), else the fast-tracing one. Either gives the same image.
BvhQuality bvh_quality_for(const Scene& scene, const RenderSettings& settings);

class SceneResources {
 public:
  // `scene` and `settings` must outlive this object. Build it inside the task arena that will
  // render, so the BVH build uses the same threads. Warnings go to `warnings` (may be null).
  // Textures are prepared first; when `cancel` becomes true meanwhile, they stop within
  // ~100 ms and textures().cancelled() is true (the rest is then built without textures).
  // Mesh BVHs come from `blas_cache` when given (Persistent Data; see Accel).
  SceneResources(const Scene& scene, const RenderSettings& settings,
                 std::vector<std::string>* warnings, const std::atomic<bool>* cancel = nullptr,
                 BlasCache* blas_cache = nullptr);
  SceneResources(const SceneResources&) = delete;
  SceneResources& operator=(const SceneResources&) = delete;

  const RenderContext& context() const { return context_; }
  const Accel& accel() const { return accel_; }
  const LightSet& lights() const { return lights_; }
  const TextureSet& textures() const { return textures_; }
  const EmissiveMeshes& emissive() const { return emissive_; }
  const EmitterSet& emitters() const { return *emitters_; }

  // Moved objects: the caller changed Scene::instances[i].object_to_world of these indices.
  // The BVH's top level is rebuilt around them (Accel::update_instance_transforms), and the
  // emissive triangles (world space) with the emitters built on them are rebuilt only when
  // they changed; textures, lamps and mesh BVHs stay. Afterwards everything equals what a
  // SceneResources built from the moved scene would hold. False when the Accel refused the
  // move (see there): build new resources then.
  bool update_instance_transforms(const std::vector<uint32_t>& scene_indices);
  // Edited materials: the caller replaced entries of Scene::materials (same textures). Shading
  // reads materials from the scene, so only the objects' shadow bits (render/shadow_ray.h), the
  // emissive triangles (their radiance and which triangles emit) and the emitters on them are
  // rebuilt, and only when they changed. False
  // when the resources were cancelled while being built (build new ones then).
  bool update_materials();

 private:
  TextureSet textures_;  // first: the BVH is not needed to convert images
  Accel accel_;
  LightSet lights_;
  EmissiveMeshes emissive_;
  // Rebuilds the emissive triangles from the scene, and the emitters when they changed.
  void refresh_emissive();

  std::unique_ptr<EmitterSet> emitters_;  // rebuilt in place when emissive triangles move
  const Scene& scene_;
  RenderContext context_;
};

}  // namespace photon

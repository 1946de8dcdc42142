// A viewport's synced scene together with what rendering derives from it (SceneResources: the
// BVH, lamps, textures, emissive triangles), kept across the progressive sessions that render
// it one after another. A session started for new settings, or after objects moved, renders
// at once instead of rebuilding them: a moved object only re-places its instance in the BVH's
// top level (as Cycles' viewport refits its top-level BVH for object transforms).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/render/blas_cache.h"
#include "photon/scene/scene.h"
#include "photon/session/scene_resources.h"

namespace photon {

class ViewportScene {
 public:
  // Mesh BVHs come from `blas_cache` when given (it must be the one of every session here).
  ViewportScene(std::shared_ptr<Scene> scene, std::shared_ptr<BlasCache> blas_cache);
  // A scene that cannot move: move_instances throws.
  ViewportScene(std::shared_ptr<const Scene> scene, std::shared_ptr<BlasCache> blas_cache);
  ViewportScene(const ViewportScene&) = delete;
  ViewportScene& operator=(const ViewportScene&) = delete;

  const Scene& scene() const { return *scene_; }
  BlasCache* blas_cache() const { return blas_cache_.get(); }

  // Moves Scene::instances[indices[k]] to `to_world[k]`. Built resources are updated in place
  // (SceneResources::update_instance_transforms) and the result is true; when they refuse the
  // move (an instance whose transform becomes or stops being usable) they are dropped, the next
  // session builds them again from the moved scene (mesh BVHs still from the cache), and the
  // result is false. Either way the next session renders exactly the moved scene. Throws
  // std::runtime_error while a session renders the scene, std::out_of_range for a bad index.
  bool move_instances(const std::vector<uint32_t>& indices, const std::vector<Transform>& to_world);

  // Replaces Scene::materials[index] (an edited material, whose textures are among the
  // scene's). Built resources keep their BVH, lamps and textures (SceneResources::
  // update_materials): true; false when they had to be dropped. The next session renders
  // exactly the edited scene. Throws like move_instances, and std::invalid_argument for a
  // material reading a texture the scene does not have.
  bool replace_material(uint32_t index, Material material);

  // How many times the resources were built, and moves applied in place (statistics, tests).
  int builds() const { return builds_.load(); }
  int moves_in_place() const { return moves_in_place_.load(); }

  // For a session's worker, which holds mutex() while it renders: the resources, built on the
  // first call (inside the caller's task arena, so the build uses its threads) with their
  // warnings appended to `warnings`; null when that build was cancelled (the next call builds
  // again). `settings` only chooses the BVH quality; sessions render with their own settings.
  const SceneResources* resources(const RenderSettings& settings, const std::atomic<bool>* cancel,
                                  std::vector<std::string>* warnings);
  bool built() const { return built_.load(); }
  // World bounds of the built BVH (what a fresh build of the scene would have); false when not
  // built, nothing is instanced, or a session is rendering.
  bool bounds(Vec3* lo, Vec3* hi);
  std::mutex& mutex() { return mutex_; }

 private:
  std::shared_ptr<const Scene> scene_;
  Scene* mutable_scene_ = nullptr;  // null for a const scene
  std::shared_ptr<BlasCache> blas_cache_;
  std::mutex mutex_;               // held by the session rendering, and by move_instances
  RenderSettings build_settings_;  // the resources' RenderContext points at it
  // Embree errors of an Accel without a cache go here (it keeps the pointer).
  std::vector<std::string> build_warnings_;
  std::unique_ptr<SceneResources> resources_;
  std::atomic<bool> built_{false};  // resources_ is set (readable while a session renders)
  std::atomic<int> builds_{0};
  std::atomic<int> moves_in_place_{0};
};

}  // namespace photon

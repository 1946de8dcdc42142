#include "photon/session/viewport_scene.h"

#include <stdexcept>

namespace photon {

ViewportScene::ViewportScene(std::shared_ptr<Scene> scene, std::shared_ptr<BlasCache> blas_cache)
    : scene_(scene), mutable_scene_(scene.get()), blas_cache_(std::move(blas_cache)) {
  if (!scene_) throw std::invalid_argument("ViewportScene: no scene");
}

ViewportScene::ViewportScene(std::shared_ptr<const Scene> scene,
                             std::shared_ptr<BlasCache> blas_cache)
    : scene_(std::move(scene)), blas_cache_(std::move(blas_cache)) {
  if (!scene_) throw std::invalid_argument("ViewportScene: no scene");
}

bool ViewportScene::move_instances(const std::vector<uint32_t>& indices,
                                   const std::vector<Transform>& to_world) {
  if (!mutable_scene_) throw std::runtime_error("ViewportScene: the scene is read-only");
  if (indices.size() != to_world.size())
    throw std::invalid_argument("ViewportScene: one transform per instance index");
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock())
    throw std::runtime_error("ViewportScene: a session is rendering the scene; cancel it first");
  for (uint32_t index : indices)
    if (index >= mutable_scene_->instances.size())
      throw std::out_of_range("ViewportScene: instance index " + std::to_string(index));
  for (size_t k = 0; k < indices.size(); ++k)
    mutable_scene_->instances[indices[k]].object_to_world = to_world[k];
  if (!resources_) return false;
  if (resources_->update_instance_transforms(indices)) {
    ++moves_in_place_;
    return true;
  }
  resources_.reset();
  built_ = false;
  return false;
}

bool ViewportScene::replace_material(uint32_t index, Material material) {
  if (!mutable_scene_) throw std::runtime_error("ViewportScene: the scene is read-only");
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock())
    throw std::runtime_error("ViewportScene: a session is rendering the scene; cancel it first");
  if (index >= mutable_scene_->materials.size())
    throw std::out_of_range("ViewportScene: material index " + std::to_string(index));
  const int64_t textures = static_cast<int64_t>(mutable_scene_->textures.size());
  for (const Closure& c : material.closures)
    for (const Input& in : c.params)
      if (in.texture >= textures)
        throw std::invalid_argument("ViewportScene: material '" + material.name +
                                    "' reads a texture the scene does not have");
  // Shading reads the scene's materials through the BVH's slots: replaced in place.
  mutable_scene_->materials[index] = std::move(material);
  if (!resources_) return false;
  if (resources_->update_materials()) return true;
  resources_.reset();
  built_ = false;
  return false;
}

bool ViewportScene::bounds(Vec3* lo, Vec3* hi) {
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !resources_ || resources_->accel().instance_count() == 0) return false;
  *lo = resources_->accel().bounds_min();
  *hi = resources_->accel().bounds_max();
  return true;
}

const SceneResources* ViewportScene::resources(const RenderSettings& settings,
                                               const std::atomic<bool>* cancel,
                                               std::vector<std::string>* warnings) {
  if (resources_) return resources_.get();
  build_settings_ = settings;
  build_warnings_.clear();
  resources_ = std::make_unique<SceneResources>(*scene_, build_settings_, &build_warnings_, cancel,
                                                blas_cache_.get());
  if (warnings) warnings->insert(warnings->end(), build_warnings_.begin(), build_warnings_.end());
  build_warnings_.clear();
  // Cancelled at any stage (an environment tabulated only in part leaves no other trace):
  // the next session builds them for real.
  if (resources_->textures().cancelled() || resources_->accel().cancelled() ||
      (cancel && cancel->load())) {
    resources_.reset();
    return nullptr;
  }
  ++builds_;
  built_ = true;
  return resources_.get();
}

}  // namespace photon

#include "photon/scene_resources.h"

namespace photon {

SceneResources::SceneResources(const Scene& scene, const RenderSettings& settings,
                               std::vector<std::string>* warnings)
    : accel_(scene, warnings),
      lights_(scene.lights, warnings),
      textures_(scene.textures, warnings),
      emissive_(scene, accel_, &textures_) {
  context_.scene = &scene;
  context_.accel = &accel_;
  context_.lights = &lights_;
  context_.settings = &settings;
  context_.emissive = &emissive_;
  context_.textures = &textures_;
}

}  // namespace photon

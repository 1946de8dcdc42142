// Everything rendering derives from a Scene before the first pixel: the BVH, the lights, the
// image textures, the emissive triangles, and the RenderContext that points at them. Render
// sessions, lighting bakes, tests and benchmarks all build it here, so none of them can forget
// a part (a bake without textures would bake untextured albedo).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "photon/accel.h"
#include "photon/emissive_mesh.h"
#include "photon/integrator.h"
#include "photon/lights.h"
#include "photon/textures.h"

namespace photon {

class SceneResources {
 public:
  // `scene` and `settings` must outlive this object. Build it inside the task arena that will
  // render, so the BVH build uses the same threads. Warnings go to `warnings` (may be null).
  SceneResources(const Scene& scene, const RenderSettings& settings,
                 std::vector<std::string>* warnings);
  SceneResources(const SceneResources&) = delete;
  SceneResources& operator=(const SceneResources&) = delete;

  const RenderContext& context() const { return context_; }
  const Accel& accel() const { return accel_; }
  const LightSet& lights() const { return lights_; }
  const TextureSet& textures() const { return textures_; }
  const EmissiveMeshes& emissive() const { return emissive_; }

 private:
  Accel accel_;
  LightSet lights_;
  TextureSet textures_;
  EmissiveMeshes emissive_;
  RenderContext context_;
};

}  // namespace photon

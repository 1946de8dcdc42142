// A scene with everything the radiosity tests need to mesh, solve and look up.
#pragma once

#include <string>
#include <vector>

#include "photon/integrators/integrator.h"
#include "photon/integrators/radiosity/radiosity_material.h"
#include "photon/integrators/radiosity/radiosity_mesh.h"
#include "photon/session/scene_resources.h"

namespace photon {

struct RadiosityFixture {
  explicit RadiosityFixture(Scene s)
      : scene(std::move(s)),
        resources(scene, settings, &warnings),
        context(resources.context()),
        accel(resources.accel()) {}
  RadiosityMesh mesh(float patch_size) {
    RadiosityMeshSettings ms;
    ms.patch_size = patch_size;
    return RadiosityMesh(scene, accel, ms, is_radiosity_surface, &warnings);
  }
  Scene scene;
  std::vector<std::string> warnings;
  RenderSettings settings;
  SceneResources resources;
  const RenderContext& context;
  const Accel& accel;
};

}  // namespace photon

// A scene with everything the radiosity tests need to mesh, solve and look up.
#pragma once

#include <string>
#include <vector>

#include "photon/emissive_mesh.h"
#include "photon/integrator.h"
#include "photon/radiosity_material.h"
#include "photon/radiosity_mesh.h"

namespace photon {

struct RadiosityFixture {
  explicit RadiosityFixture(Scene s)
      : scene(std::move(s)),
        accel(scene, &warnings),
        lights(scene.lights, &warnings),
        emissive(scene, accel) {
    context = {&scene, &accel, &lights, &settings, &emissive};
  }
  RadiosityMesh mesh(float patch_size) {
    RadiosityMeshSettings ms;
    ms.patch_size = patch_size;
    return RadiosityMesh(scene, accel, ms, is_radiosity_surface, &warnings);
  }
  Scene scene;
  std::vector<std::string> warnings;
  Accel accel;
  LightSet lights;
  EmissiveMeshes emissive;
  RenderSettings settings;
  RenderContext context;
};

}  // namespace photon

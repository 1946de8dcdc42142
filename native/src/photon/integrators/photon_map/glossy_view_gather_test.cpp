// A diffuse surface seen through a rough glossy reflection is shaded like one seen directly or
// through a perfect mirror: by final gathering, not by the global photon map's own estimate
// (Jensen 1996, "Global Illumination using Photon Maps": the approximate evaluation only once
// the path has been reflected diffusely). The scene makes the map's estimate badly biased on
// purpose: a small patch lit only indirectly, whose k-nearest disc reaches far past its edges.
#include <gtest/gtest.h>

#include <memory>

#include "photon/integrators/photon_map/photon_map_integrator.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace glossy_view_gather_test {
namespace {

// A 0.2 m diffuse patch at z = 0 under a 4 m diffuse ceiling at z = 1, lit by a point light
// just under the ceiling that a black 1 m square below it hides from the patch and from the
// mirror: the patch gets only light reflected by the ceiling. A vertical mirror at y = 0.5
// shows the patch to a camera at (0, -0.5, 0.6) whose narrow view holds nothing else.
Scene patch_seen_in_mirror(float mirror_roughness) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f), "patch"));
  scene.materials.push_back(Material::diffuse(Vec3(0.8f), "ceiling"));
  scene.materials.push_back(Material::diffuse(Vec3(0.0f), "occluder"));
  Material mirror = Material::mirror(Vec3(1.0f));
  if (mirror_roughness > 0.0f) {
    mirror.closures[0].sharp = false;
    mirror.closures[0][Param::kRoughness] = Input::constant(mirror_roughness);
  }
  scene.materials.push_back(mirror);
  add_mesh_instance(&scene, make_quad({-0.1f, -0.1f, 0.0f}, {0.2f, 0, 0}, {0, 0.2f, 0}), 0);
  add_mesh_instance(&scene, make_quad({-2, -2, 1}, {4, 0, 0}, {0, 4, 0}), 1);
  add_mesh_instance(&scene, make_quad({-0.5f, -0.5f, 0.85f}, {1, 0, 0}, {0, 1, 0}), 2);
  add_mesh_instance(&scene, make_quad({-0.5f, 0.5f, 0.05f}, {1, 0, 0}, {0, 0, 0.75f}), 3);
  Light light;
  light.type = LightType::kPoint;
  light.power = 200.0f;
  light.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 0.9f));
  scene.lights.push_back(light);
  // The patch's mirror image is centred on (0, 1, 0), 1.6 m away: 0.1 rad stays inside it.
  scene.camera = make_look_at_camera({0.0f, -0.5f, 0.6f}, {0.0f, 1.0f, 0.0f}, 0.1f, 1.0f);
  return scene;
}

double mean_red(const Scene& scene, uint64_t seed) {
  RenderSettings s;
  s.full_width = s.full_height = 8;
  s.x1 = s.y1 = 8;
  s.samples = 16;
  s.seed = seed;
  s.integrator = IntegratorType::kPhotonMap;
  s.photons = 20000;
  s.caustic_photons = 0;
  s.gather_count = 200;  // a disc far wider than the patch: the map's estimate is biased low
  s.final_gather_rays = 32;
  s.irradiance_cache = false;  // its records are placed through delta lobes only
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  const std::vector<float> rgba = session.image();
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i];
  return sum / (rgba.size() / 4);
}

TEST(GlossyViewGather, PatchThroughARoughMirrorMatchesThePatchThroughAPerfectMirror) {
  // Roughness 0.05 (GGX alpha 0.0025) is a rough lobe, yet reflects almost like the mirror.
  const double sharp = mean_red(patch_seen_in_mirror(0.0f), 5);
  const double rough = mean_red(patch_seen_in_mirror(0.05f), 5);
  ASSERT_GT(sharp, 0.0);
  // The global map's estimate over its 200-photon disc (the patch holds fewer) gave a tenth.
  EXPECT_NEAR(rough / sharp, 1.0, 0.05) << "sharp " << sharp << ", rough " << rough;
}

}  // namespace
}  // namespace glossy_view_gather_test
}  // namespace photon

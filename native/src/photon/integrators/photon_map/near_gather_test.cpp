// Final-gather rays that hit a surface nearer than the global map's estimate radius take one
// more bounce there (a secondary final gather) instead of reading that surface's record: a
// record on a small object is a k-nearest estimate over a disc about as wide as the object, so
// the light it sends to the floor beside it depended on how many photons were traced.
#include <gtest/gtest.h>

#include <memory>

#include "photon/integrators/photon_map/photon_map_integrator.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace near_gather_test {
namespace {

// A 0.4 m diffuse ball resting on a 6 m diffuse floor under a uniform sky; an orthographic
// camera looks straight down at the floor just beside the ball, lit by the sky and by the ball.
Scene ball_on_floor() {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f), "floor"));
  scene.materials.push_back(Material::diffuse(Vec3(0.9f), "ball"));
  add_mesh_instance(&scene, make_quad({-3, -3, 0}, {6, 0, 0}, {0, 6, 0}), 0);
  add_mesh_instance(&scene, make_uv_sphere({0.0f, 0.0f, 0.4f}, 0.4f, 64, 32), 1);
  scene.world = World::uniform(Vec3(1.0f));
  scene.camera.projection = Projection::kOrthographic;
  scene.camera.set_camera_to_world(Transform::translation(Vec3(0.51f, 0.0f, 3.0f)));
  scene.camera.window_min_x = scene.camera.window_min_y = -0.09f;
  scene.camera.window_max_x = scene.camera.window_max_y = 0.09f;
  return scene;
}

double mean_red(uint64_t photons) {
  RenderSettings s;
  s.full_width = s.full_height = 8;
  s.x1 = s.y1 = 8;
  s.samples = 16;
  s.seed = 9;
  s.integrator = IntegratorType::kPhotonMap;
  s.photons = photons;
  s.caustic_photons = 0;
  s.final_gather_rays = 32;
  s.irradiance_cache = false;
  RenderSession session(std::make_shared<Scene>(ball_on_floor()), s);
  session.start();
  session.wait();
  const std::vector<float> rgba = session.image();
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i];
  return sum / (rgba.size() / 4);
}

TEST(NearGather, FloorBesideABallDoesNotDependOnThePhotonCount) {
  // With 400k photons the estimates are narrower than the gather rays' lengths here (no
  // secondary gathers); with 10k the ball's records were 6% off that, now 1%.
  const double few = mean_red(10000), many = mean_red(400000);
  ASSERT_GT(many, 0.0);
  EXPECT_NEAR(few / many, 1.0, 0.03) << "10k photons " << few << ", 400k photons " << many;
}

}  // namespace
}  // namespace near_gather_test
}  // namespace photon

#include "photon/integrators/photon_map/photon_map_integrator.h"

#include <gtest/gtest.h>

#include <memory>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace photon_map_integrator_test {
namespace {

RenderSettings settings_for(int size, int spp) {
  RenderSettings s;
  s.full_width = s.full_height = size;
  s.x1 = s.y1 = size;
  s.samples = spp;
  s.seed = 3;
  s.integrator = IntegratorType::kPhotonMap;
  s.light_passes = true;
  return s;
}

struct Rendered {
  std::vector<float> rgba;
  RenderStats stats;
};

Rendered render(const Scene& scene, const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  return {session.image(), session.stats()};
}

double mean_channel(const std::vector<float>& rgba, int c) {
  double sum = 0.0;
  for (size_t i = c; i < rgba.size(); i += 4) sum += rgba[i];
  return sum / (rgba.size() / 4);
}

// A closed box whose walls emit Le and reflect albedo rho: every wall sends
// L = Le + rho L, so L = Le / (1 - rho) everywhere (a furnace-like test of the
// rendering equation's four terms together).
Scene emissive_furnace(float rho, float le) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(rho)).with_emission(Vec3(le)));
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  scene.camera = make_look_at_camera({0, -0.5f, 0}, {0, 1, 0.2f}, 1.2f, 1.0f);
  return scene;
}

TEST(PhotonMapIntegrator, EmissiveFurnaceConvergesToLeOverOneMinusAlbedo) {
  // Final gathering through the irradiance cache, per sample, and the preview.
  for (auto [final_gather, cache] :
       {std::pair{16, true}, std::pair{16, false}, std::pair{0, false}}) {
    const Scene scene = emissive_furnace(0.6f, 1.0f);
    RenderSettings s = settings_for(24, 8);
    s.photons = 100000;
    s.final_gather_rays = final_gather;
    s.irradiance_cache = cache;
    const Rendered r = render(scene, s);
    EXPECT_NEAR(mean_channel(r.rgba, 0), 1.0 / (1.0 - 0.6), 0.03 * 2.5)
        << "final gather rays " << final_gather << ", cache " << cache;
    const auto& built = r.stats.integrator.irradiance_cache;
    EXPECT_EQ(built.has_value() && built->records > 0, cache);
  }
}

// A diffuse plane under a point light of intensity I at height h: E = I cos(theta) / d^2 and,
// with nothing else in the scene, no indirect light.
TEST(PhotonMapIntegrator, PlaneUnderPointLightMatchesInverseSquareLaw) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 0);
  Light light;
  light.type = LightType::kPoint;
  light.power = 100.0f;
  const float h = 1.0f;
  light.light_to_world = Transform::translation(Vec3(0, 0, h));
  scene.lights.push_back(light);
  // Orthographic, looking straight down on [-0.33, 0.33]^2 with 33 x 33 pixels of 0.02 m.
  scene.camera.projection = Projection::kOrthographic;
  scene.camera.set_camera_to_world(Transform::translation(Vec3(0, 0, 3)));
  scene.camera.window_min_x = scene.camera.window_min_y = -0.33f;
  scene.camera.window_max_x = scene.camera.window_max_y = 0.33f;
  RenderSettings s = settings_for(33, 16);
  s.photons = 20000;
  const Rendered r = render(scene, s);
  const double intensity = 100.0 / (4.0 * kPi);
  auto pixel = [&](int x, int y) { return r.rgba[(static_cast<size_t>(y) * 33 + x) * 4]; };
  EXPECT_NEAR(pixel(16, 16), 0.5 / kPi * intensity / (h * h), 0.01 * 0.5 / kPi * intensity);
  // 0.3 m from the centre along x and along y (symmetric, so the image orientation is moot).
  const double rr = 0.3, d2 = h * h + rr * rr;
  const double expected = 0.5 / kPi * intensity * (h / std::sqrt(d2)) / d2;
  for (auto [x, y] : {std::pair{1, 16}, std::pair{31, 16}, std::pair{16, 1}, std::pair{16, 31}})
    EXPECT_NEAR(pixel(x, y), expected, 0.01 * expected) << x << "," << y;
}

TEST(PhotonMapIntegrator, CausticBoxIsThreadIndependentAndHasACaustic) {
  Scene scene = make_caustic_box();
  RenderSettings s = settings_for(32, 2);
  s.photons = 20000;
  s.caustic_photons = 20000;
  s.final_gather_rays = 4;
  s.threads = 1;
  const Rendered one = render(scene, s);
  s.threads = 2;
  s.tile_size = 8;
  const Rendered two = render(scene, s);
  EXPECT_EQ(one.rgba, two.rgba);
  ASSERT_TRUE(two.stats.integrator.photon_map.has_value());
  // Aimed photons leave the sphere light's surface; those from its far side carry no
  // power, so about 40% of the 20000 are stored (isotropic emission: under 10%).
  EXPECT_GT(two.stats.integrator.photon_map->caustic_photons_stored, 6000u);
}

TEST(PhotonMapIntegrator, EmptySceneAndNoLightsRenderBlackWithoutPhotons) {
  Scene empty;
  RenderSettings s = settings_for(8, 1);
  const Rendered r = render(empty, s);
  EXPECT_EQ(mean_channel(r.rgba, 0), 0.0);
  Scene dark = make_cornell_box();
  dark.lights.clear();
  const Rendered d = render(dark, s);
  EXPECT_EQ(mean_channel(d.rgba, 0), 0.0);
}

}  // namespace
}  // namespace photon_map_integrator_test
}  // namespace photon

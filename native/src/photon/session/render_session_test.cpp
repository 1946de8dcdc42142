#include "photon/session/render_session.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "photon/testing/test_scenes.h"

namespace photon {
namespace render_session_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

struct RenderOutput {
  std::vector<float> image;
  std::vector<std::string> warnings;
  RenderStats stats;
  std::string status;
  bool finished = false;
  bool cancelled = false;
};

RenderOutput render(std::shared_ptr<const Scene> scene, const RenderSettings& settings) {
  RenderSession session(std::move(scene), settings);
  session.start();
  session.wait();
  RenderOutput out;
  out.image = session.image();
  out.warnings = session.warnings();
  out.stats = session.stats();
  out.status = session.status();
  out.finished = session.finished();
  out.cancelled = session.cancelled();
  return out;
}

RenderSettings small_settings(int width, int height, int spp) {
  RenderSettings s;
  s.full_width = width;
  s.full_height = height;
  s.x0 = 0;
  s.y0 = 0;
  s.x1 = width;
  s.y1 = height;
  s.samples = spp;
  s.seed = 17;
  // Small photon counts keep the photon-mapped renders quick.
  s.photons = 20000;
  s.caustic_photons = 10000;
  s.final_gather_rays = 4;
  return s;
}

std::shared_ptr<const Scene> cornell() {
  return std::make_shared<Scene>(make_cornell_box());
}

TEST(RenderSession, CornellBoxRendersSomethingFinite) {
  RenderSettings s = small_settings(48, 48, 4);
  s.threads = 2;
  const RenderOutput out = render(cornell(), s);
  EXPECT_TRUE(out.finished);
  EXPECT_FALSE(out.cancelled);
  EXPECT_EQ(out.status, "Done");
  EXPECT_TRUE(out.warnings.empty()) << out.warnings.front();
  ASSERT_EQ(out.image.size(), 48u * 48u * 4u);
  double sum = 0.0;
  for (float v : out.image) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    sum += v;
  }
  EXPECT_GT(sum, 0.0);
  EXPECT_EQ(out.stats.camera_samples, 48u * 48u * 4u);
  EXPECT_EQ(out.stats.non_finite_samples, 0u);
  EXPECT_EQ(out.stats.instances, 7u);
  EXPECT_EQ(out.stats.lights, 1u);
  EXPECT_EQ(out.stats.threads, 2);
}

TEST(RenderSession, ImageDoesNotDependOnThreadsOrTiles) {
  RenderSettings a = small_settings(48, 48, 4);
  a.threads = 1;
  a.tile_size = 8;
  RenderSettings b = a;
  b.threads = 2;
  b.tile_size = 32;
  RenderSettings c = a;
  c.threads = 2;
  c.tile_size = 5;  // tiles that do not divide the image
  const auto scene = cornell();
  const std::vector<float> ia = render(scene, a).image;
  const std::vector<float> ib = render(scene, b).image;
  const std::vector<float> ic = render(scene, c).image;
  ASSERT_EQ(ia.size(), ib.size());
  EXPECT_TRUE(ia == ib);  // bit-identical
  EXPECT_TRUE(ia == ic);
  // A different seed gives a different (noisy) image, so the comparison above is meaningful.
  RenderSettings d = a;
  d.seed = 18;
  EXPECT_FALSE(ia == render(scene, d).image);
}

TEST(RenderSession, RenderBorderMatchesTheFullFrame) {
  const auto scene = cornell();
  RenderSettings full = small_settings(48, 48, 4);
  full.threads = 2;
  const std::vector<float> whole = render(scene, full).image;

  RenderSettings border = full;
  border.x0 = 10;
  border.y0 = 13;
  border.x1 = 30;
  border.y1 = 40;
  border.tile_size = 8;
  RenderSession session(scene, border);
  ASSERT_EQ(session.region_width(), 20);
  ASSERT_EQ(session.region_height(), 27);
  session.start();
  // Collect the tiles as they come and assemble them ourselves.
  std::vector<float> assembled(20 * 27 * 4, -1.0f);
  std::vector<int> covered(20 * 27, 0);
  while (true) {
    const bool was_finished = session.finished();
    for (const Tile& tile : session.take_tiles(0.5)) {
      ASSERT_EQ(tile.rgba.size(), static_cast<size_t>(tile.width) * tile.height * 4);
      for (int y = 0; y < tile.height; ++y)
        for (int x = 0; x < tile.width; ++x) {
          const int px = tile.x + x, py = tile.y + y;
          ASSERT_LT(px, 20);
          ASSERT_LT(py, 27);
          ++covered[py * 20 + px];
          for (int k = 0; k < 4; ++k)
            assembled[(py * 20 + px) * 4 + k] = tile.rgba[(y * tile.width + x) * 4 + k];
        }
    }
    if (was_finished) break;
  }
  session.wait();
  for (int c : covered) EXPECT_EQ(c, 1);
  const std::vector<float> region = session.image();
  EXPECT_TRUE(region == assembled);
  for (int y = 0; y < 27; ++y)
    for (int x = 0; x < 20; ++x)
      for (int k = 0; k < 4; ++k)
        ASSERT_EQ(region[(y * 20 + x) * 4 + k], whole[((y + 13) * 48 + (x + 10)) * 4 + k])
            << "pixel " << x + 10 << ", " << y + 13 << " channel " << k;
}

TEST(RenderSession, CancelStopsPromptly) {
  // Far too much work to finish within the test: 1024^2 pixels at 64 samples.
  RenderSettings s = small_settings(1024, 1024, 64);
  s.threads = 2;
  s.tile_size = 16;
  using Clock = std::chrono::steady_clock;
  {
    RenderSession session(cornell(), s);
    session.start();
    session.cancel();
    const auto t0 = Clock::now();
    session.wait();
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 2.0);
    EXPECT_TRUE(session.finished());
    EXPECT_TRUE(session.cancelled());
    EXPECT_EQ(session.status(), "Cancelled");
  }
  {
    // Cancel in the middle of rendering, once tiles have started to arrive. Without the
    // irradiance cache, whose build at 1024^2 outlasts the wait for the first tile
    // (irradiance_cache_render_test.cpp cancels during the build).
    RenderSettings no_cache = s;
    no_cache.irradiance_cache = false;
    RenderSession session(cornell(), no_cache);
    session.start();
    std::vector<Tile> first = session.take_tiles(10.0);
    EXPECT_FALSE(first.empty());
    session.cancel();
    const auto t0 = Clock::now();
    session.wait();
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 2.0);
    EXPECT_TRUE(session.finished());
    EXPECT_LT(session.progress(), 1.0f);
    EXPECT_EQ(session.stats().camera_samples, 0u);  // an incomplete render reports no total
  }
}

TEST(RenderSession, EmptySceneRendersBlack) {
  auto scene = std::make_shared<Scene>();
  const RenderOutput out = render(scene, small_settings(16, 12, 2));
  EXPECT_TRUE(out.finished);
  EXPECT_EQ(out.status, "Done");
  EXPECT_TRUE(out.warnings.empty()) << out.warnings.front();
  ASSERT_EQ(out.image.size(), 16u * 12u * 4u);
  // Black, and opaque as Blender's engines are without Film > Transparent.
  for (size_t i = 0; i < out.image.size(); ++i) EXPECT_EQ(out.image[i], i % 4 == 3 ? 1.0f : 0.0f);
}

TEST(RenderSession, WorldOnlySceneRendersTheWorldColour) {
  auto scene = std::make_shared<Scene>();
  const Vec3 w(0.125f, 0.5f, 3.0f);  // exactly representable: averaging must give it back
  scene->world.color = w;
  const RenderOutput out = render(scene, small_settings(16, 12, 4));
  ASSERT_EQ(out.image.size(), 16u * 12u * 4u);
  for (size_t i = 0; i < out.image.size(); i += 4) {
    ASSERT_EQ(out.image[i + 0], w.x);
    ASSERT_EQ(out.image[i + 1], w.y);
    ASSERT_EQ(out.image[i + 2], w.z);
    ASSERT_EQ(out.image[i + 3], 1.0f);  // opaque without Film > Transparent
  }
  RenderSettings transparent = small_settings(16, 12, 4);
  transparent.transparent_background = true;
  for (float v : render(scene, transparent).image) ASSERT_EQ(v, 0.0f);
}

// A large diffuse floor (albedo rho) at z = 0 and a camera at `camera_height` looking straight
// down (its -Z is world -Z) with a tiny field of view.
std::shared_ptr<Scene> floor_scene(const Vec3& albedo, float camera_height) {
  auto scene = std::make_shared<Scene>();
  scene->materials.push_back(Material::diffuse(albedo, "floor"));
  add_mesh_instance(scene.get(), make_quad({-100, -100, 0}, {200, 0, 0}, {0, 200, 0}), 0);
  const float cam_rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, camera_height};
  scene->camera.camera_to_world = Transform::from_rows(cam_rows);
  scene->camera.window_min_x = scene->camera.window_min_y = -1e-3f;
  scene->camera.window_max_x = scene->camera.window_max_y = 1e-3f;
  return scene;
}

TEST(RenderSession, DiffuseFloorUnderAPointLightHasTheAnalyticRadiance) {
  // Point light of power P at height h over a large Lambertian floor of albedo rho: irradiance
  // straight below E = P / (4 pi h^2), outgoing radiance rho / pi * E.
  const float power = 100.0f, h = 2.0f;
  const Vec3 albedo(0.2f, 0.5f, 0.8f);
  auto scene = floor_scene(albedo, 1.0f);
  Light light;
  light.type = LightType::kPoint;
  light.power = power;
  const float light_rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, h};
  light.light_to_world = Transform::from_rows(light_rows);
  scene->lights.push_back(light);

  const RenderOutput out = render(scene, small_settings(4, 4, 4));
  EXPECT_TRUE(out.warnings.empty());
  const double e = power / (4.0 * kPiD * h * h);
  for (size_t i = 0; i < out.image.size(); i += 4) {
    for (int k = 0; k < 3; ++k) {
      const double expected = albedo[k] / kPiD * e;
      EXPECT_NEAR(out.image[i + k], expected, 0.01 * expected)
          << "pixel " << i / 4 << " channel " << k;
    }
    EXPECT_EQ(out.image[i + 3], 1.0f);
  }
}

// A point light whose radius is far below what float positions resolve (1e-12 m and less at
// 2 m) is a point light: its disc's area underflows and its radiance overflows otherwise.
TEST(RenderSession, PointLightOfTinyRadiusLightsLikeAPoint) {
  const float power = 100.0f, h = 2.0f;
  const Vec3 albedo(0.5f);
  const double expected = 0.5 / kPiD * power / (4.0 * kPiD * h * h);
  for (const float radius : {1e-7f, 1e-12f, 1e-20f, 1e-30f, 1e-44f}) {
    auto scene = floor_scene(albedo, 1.0f);
    Light light;
    light.type = LightType::kPoint;
    light.power = power;
    light.radius = radius;
    const float light_rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, h};
    light.light_to_world = Transform::from_rows(light_rows);
    scene->lights.push_back(light);
    const RenderOutput out = render(scene, small_settings(4, 4, 4));
    for (size_t i = 0; i < out.image.size(); i += 4)
      EXPECT_NEAR(out.image[i], expected, 0.01 * expected) << "radius " << radius;
  }
}

TEST(RenderSession, DiffuseFloorUnderASquareAreaLightHasTheAnalyticRadiance) {
  // Square light of side s at height h facing down, radiance L = P / (4 s^2). On its axis, four
  // a x a corner rectangles (a = s / 2), each contributing
  // L int int h^2 / r^4 = (L / 2) * 2 a / sqrt(a^2 + h^2) atan(a / sqrt(a^2 + h^2)),
  // give E = 4 L a / sqrt(a^2 + h^2) atan(a / sqrt(a^2 + h^2)) (-> pi L as a -> infinity).
  const float power = 40.0f, side = 1.0f, h = 1.5f;
  const Vec3 albedo(0.7f, 0.4f, 0.1f);
  auto scene = floor_scene(albedo, 0.5f);  // camera below the light
  Light light;
  light.type = LightType::kArea;
  light.power = power;
  light.size_x = light.size_y = side;
  const float rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, h};
  light.light_to_world = Transform::from_rows(rows);
  scene->lights.push_back(light);
  const RenderOutput out = render(scene, small_settings(2, 2, 256));
  const double a = side / 2.0, sa = std::sqrt(a * a + h * h);
  const double radiance = power / (4.0 * side * side);
  const double e = 4.0 * radiance * (a / sa) * std::atan(a / sa);
  for (size_t i = 0; i < out.image.size(); i += 4)
    for (int k = 0; k < 3; ++k) {
      const double expected = albedo[k] / kPiD * e;
      EXPECT_NEAR(out.image[i + k], expected, 0.01 * expected)
          << "pixel " << i / 4 << " channel " << k;
    }
}

TEST(RenderSession, DiffuseFloorUnderAUniformWorldReflectsAlbedoTimesWorld) {
  // E = pi W from an unoccluded uniform sky, so the outgoing radiance is rho W for every sample
  // (a shadow ray that re-hit its own floor would make some samples black).
  const Vec3 albedo(0.25f, 0.5f, 0.75f), world(0.4f, 1.0f, 2.0f);
  auto scene = floor_scene(albedo, 1.0f);
  scene->world.color = world;
  const RenderOutput out = render(scene, small_settings(4, 4, 16));
  for (size_t i = 0; i < out.image.size(); i += 4) {
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(out.image[i + k], albedo[k] * world[k], 1e-5f * world[k]) << "pixel " << i / 4;
    EXPECT_EQ(out.image[i + 3], 1.0f);
  }
}

// Regression test for a bug in photon/rng.h as of commit 109ae12: the pixel jitter (first
// get_2d) and the lens sample (second get_2d) were the same R2 points up to a constant shift,
// so depth of field converged to a wrong, seed-dependent value (0.17 to 0.87 here). Setup: an
// orthographic camera one unit above an emissive half-plane (x < 0, radiance 1), one pixel covering
// the window [-1, 1]^2, aperture radius 1/2 focused at 1/3: a camera ray from film x with lens disc
// point d hits x - d.x (origin x + d.x / 2 heading to the focus point (x, -1/3), reaching depth
// 1 at x + d.x / 2 - 3 d.x / 2). x is uniform on [-1, 1] and d.x symmetric about 0, so the hit
// point is symmetric about 0 and the pixel's exact value is 1/2, whatever the seed.
TEST(RenderSession, DepthOfFieldConvergesToTheExactPixelValue) {
  auto scene = std::make_shared<Scene>();
  // No reflection: the pixel sees emission only.
  scene->materials.push_back(Material::emission(Vec3(1.0f), "glow"));
  add_mesh_instance(scene.get(), make_quad({-100, -100, 0}, {100, 0, 0}, {0, 200, 0}), 0);
  Camera& cam = scene->camera;
  cam.projection = Projection::kOrthographic;
  const float rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1.0f};
  cam.camera_to_world = Transform::from_rows(rows);
  cam.window_min_x = cam.window_min_y = -1.0f;
  cam.window_max_x = cam.window_max_y = 1.0f;
  cam.clip_start = 0.01f;
  cam.aperture_radius = 0.5f;
  cam.focus_distance = 1.0f / 3.0f;
  for (uint64_t seed = 0; seed < 4; ++seed) {
    RenderSettings s = small_settings(1, 1, 8192);
    s.seed = seed;
    s.threads = 1;
    const RenderOutput out = render(scene, s);
    // Binomial standard error with independent samples: 0.0055.
    EXPECT_NEAR(out.image[0], 0.5f, 0.025f) << "seed " << seed;
  }
}

}  // namespace
}  // namespace render_session_test
}  // namespace photon

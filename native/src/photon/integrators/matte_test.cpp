// Holdouts and shadow catchers seen by camera rays (matte.h), through whole renders.
#include "photon/integrators/matte.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <memory>
#include <vector>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace matte_test {
namespace {

constexpr int kSize = 8;

std::vector<float> render(std::shared_ptr<const Scene> scene, IntegratorType integrator,
                          bool transparent_film) {
  RenderSettings s;
  s.full_width = s.full_height = kSize;
  s.x0 = s.y0 = 0;
  s.x1 = s.y1 = kSize;
  s.samples = 4;
  s.seed = 3;
  s.integrator = integrator;
  s.transparent_background = transparent_film;
  s.photons = 5000;
  s.caustic_photons = 0;
  s.final_gather_rays = 2;
  s.radiosity_rays = 200000;
  RenderSession session(std::move(scene), s);
  session.start();
  session.wait();
  return session.image();
}

// A 10 m floor at z = 0 of `material` filling the view of a camera 2 m above it looking down.
std::shared_ptr<Scene> floor_scene(const Material& material) {
  auto scene = std::make_shared<Scene>();
  scene->materials.push_back(material);
  add_mesh_instance(scene.get(), make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  const float cam_rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 2};
  scene->camera.camera_to_world = Transform::from_rows(cam_rows);
  scene->camera.window_min_x = scene->camera.window_min_y = -0.1f;
  scene->camera.window_max_x = scene->camera.window_max_y = 0.1f;
  Light sun;
  sun.type = LightType::kSun;
  sun.power = 3.0f;
  scene->lights.push_back(sun);  // straight down
  return scene;
}

// `a` with weight 1 - fac plus `b` with weight fac: a Mix Shader.
Material mix(const Material& a, const Material& b, float fac) {
  Material m;
  for (Closure c : a.closures) {
    c.weight.push_back({Input::constant(fac), true});
    m.closures.push_back(c);
  }
  for (Closure c : b.closures) {
    c.weight.push_back({Input::constant(fac), false});
    m.closures.push_back(c);
  }
  return m;
}

Material holdout() {
  Closure c;
  c.type = ClosureType::kHoldout;
  return Material{"holdout", {c}};
}

Material transparent() {
  Closure c;
  c.type = ClosureType::kTransparent;
  c[Param::kColor] = Input::constant(1.0f);
  return Material{"transparent", {c}};
}

void expect_every_pixel(const std::vector<float>& image, const float rgba[4], float tolerance) {
  ASSERT_EQ(image.size(), static_cast<size_t>(kSize * kSize * 4));
  for (size_t i = 0; i < image.size(); ++i)
    ASSERT_NEAR(image[i], rgba[i % 4], tolerance) << "pixel " << i / 4 << " channel " << i % 4;
}

TEST(Matte, HoldoutClosureCutsAHoleWithOrWithoutTransparentFilm) {
  for (IntegratorType integrator :
       {IntegratorType::kRayTrace, IntegratorType::kPhotonMap, IntegratorType::kRadiosity}) {
    auto scene = floor_scene(holdout());
    scene->world.color = Vec3(0.5f);
    const float hole[4] = {0, 0, 0, 0};
    expect_every_pixel(render(scene, integrator, false), hole, 0.0f);
    expect_every_pixel(render(scene, integrator, true), hole, 0.0f);
  }
}

TEST(Matte, HalfHoldoutKeepsHalfTheDiffuseAndHalfTheAlpha) {
  const Material white = Material::diffuse(Vec3(1.0f));
  auto full = floor_scene(white);
  auto half = floor_scene(mix(white, holdout(), 0.5f));
  const std::vector<float> a = render(full, IntegratorType::kRayTrace, true);
  const std::vector<float> b = render(half, IntegratorType::kRayTrace, true);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) {
      EXPECT_FLOAT_EQ(a[i], 1.0f);
      EXPECT_FLOAT_EQ(b[i], 0.5f);
    } else {
      // The sun straight down on a white floor: radiance 3 / pi, halved by the mix.
      EXPECT_NEAR(a[i], 3.0f / kPi, 1e-3f);
      EXPECT_NEAR(b[i], 0.5f * a[i], 1e-4f);
    }
  }
}

TEST(Matte, ObjectHoldoutKeepsOnlyItsTransparency) {
  // 3/4 diffuse, 1/4 transparent, held out: 3/4 of the pixel is a hole, the world shows
  // through the transparent quarter (the diffuse part is not lit or drawn).
  auto scene = floor_scene(mix(Material::diffuse(Vec3(1.0f)), transparent(), 0.25f));
  scene->instances[0].holdout = true;
  const Vec3 w(0.5f, 0.25f, 1.0f);
  scene->world.color = w;
  const float opaque_film[4] = {0.25f * w.x, 0.25f * w.y, 0.25f * w.z, 0.25f};
  expect_every_pixel(render(scene, IntegratorType::kRayTrace, false), opaque_film, 1e-6f);
  const float transparent_film[4] = {0, 0, 0, 0};
  expect_every_pixel(render(scene, IntegratorType::kRayTrace, true), transparent_film, 1e-6f);
}

TEST(Matte, HoldoutStillCastsShadows) {
  // A held-out roof the camera does not see shades the floor as any other object would.
  auto lit = floor_scene(Material::diffuse(Vec3(1.0f)));
  auto shadowed = floor_scene(Material::diffuse(Vec3(1.0f)));
  shadowed->materials.push_back(holdout());
  add_mesh_instance(shadowed.get(), make_quad({-6, -6, 5}, {12, 0, 0}, {0, 12, 0}), 1);
  shadowed->instances.back().holdout = true;
  shadowed->instances.back().visibility = kVisibleAll & ~kVisibleCamera;
  const std::vector<float> a = render(lit, IntegratorType::kRayTrace, false);
  const std::vector<float> b = render(shadowed, IntegratorType::kRayTrace, false);
  EXPECT_GT(a[0], 0.5f);
  EXPECT_EQ(b[0], 0.0f);
  EXPECT_EQ(b[3], 1.0f);
}

TEST(Matte, ShadowCatcherShowsOnlyTheShadowRatio) {
  for (IntegratorType integrator :
       {IntegratorType::kRayTrace, IntegratorType::kPhotonMap, IntegratorType::kRadiosity}) {
    SCOPED_TRACE(static_cast<int>(integrator));
    // Unshadowed: nothing of the catcher shows (transparent, or the world as it is).
    auto open = floor_scene(Material::diffuse(Vec3(0.8f)));
    open->instances[0].shadow_catcher = true;
    const Vec3 w(0.125f, 0.25f, 0.5f);
    open->world.color = w;
    const float clear[4] = {0, 0, 0, 0};
    expect_every_pixel(render(open, integrator, true), clear, 0.0f);
    const float world[4] = {w.x, w.y, w.z, 1.0f};
    expect_every_pixel(render(open, integrator, false), world, 0.0f);

    // In full shadow (a closed box round the scene that the camera does not see blocks the
    // sun and the world): opaque black with Film > Transparent, black over the world without.
    auto roofed = std::make_shared<Scene>(*open);
    roofed->materials.push_back(Material::diffuse(Vec3(0.5f)));
    add_mesh_instance(roofed.get(), make_box({-6, -6, -1}, {6, 6, 5}), 1);
    roofed->instances.back().visibility = kVisibleAll & ~kVisibleCamera;
    const float shadow[4] = {0, 0, 0, 1};
    expect_every_pixel(render(roofed, integrator, true), shadow, 0.0f);
    expect_every_pixel(render(roofed, integrator, false), shadow, 0.0f);
  }
}

TEST(Matte, ShadowCatcherSeenInAMirrorIsAnOrdinarySurface) {
  // Only camera rays see the matte: the camera looks down at a mirror floor, which reflects the
  // underside of a catcher above the camera, lit by a lamp between them. Seen in the mirror the
  // catcher is a lit diffuse surface, not a filter onto the (black) world.
  auto scene = floor_scene(Material::mirror(Vec3(1.0f)));
  scene->materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(scene.get(), make_quad({-6, -6, 3}, {0, 12, 0}, {12, 0, 0}), 1);
  scene->instances.back().shadow_catcher = true;
  Light lamp;
  lamp.type = LightType::kPoint;
  lamp.power = 100.0f;
  lamp.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 2.5f));
  scene->lights.push_back(lamp);
  const std::vector<float> image = render(scene, IntegratorType::kRayTrace, true);
  for (size_t i = 0; i < image.size(); i += 4) {
    ASSERT_GT(image[i], 1.0f) << "pixel " << i / 4;
    ASSERT_EQ(image[i + 3], 1.0f);
  }
}

TEST(Matte, ShadowCatcherUnderAbsurdLampsStaysFinite) {
  // Eight suns of the largest float power: their light (0.8 / pi of it each) sums to inf with
  // and without shadows; the unshadowed catcher must still show the world, not drop every
  // sample as inf / inf = NaN.
  auto scene = floor_scene(Material::diffuse(Vec3(0.8f)));
  scene->lights[0].power = FLT_MAX;
  for (int i = 0; i < 7; ++i) scene->lights.push_back(scene->lights[0]);
  scene->instances[0].shadow_catcher = true;
  const Vec3 w(0.125f, 0.25f, 0.5f);
  scene->world.color = w;
  const float world[4] = {w.x, w.y, w.z, 1.0f};
  expect_every_pixel(render(scene, IntegratorType::kRayTrace, false), world, 0.0f);
}

}  // namespace
}  // namespace matte_test
}  // namespace photon

#include "photon/session/viewport_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "photon/session/progressive_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace viewport_scene_test {
namespace {

RenderSettings settings(IntegratorType type) {
  RenderSettings s;
  s.integrator = type;
  s.full_width = s.full_height = 40;
  s.x0 = s.y0 = 0;
  s.x1 = s.y1 = 40;
  s.samples = 4;
  s.seed = 11;
  s.photons = 20000;
  s.caustic_photons = 10000;
  s.final_gather_rays = 4;
  s.threads = 2;
  return s;
}

// Every sample of one session, then the session ends (the ViewportScene is free again).
std::vector<float> render(ProgressiveSession& session, int samples) {
  session.start();
  EXPECT_EQ(session.wait_for_samples(samples, 120.0), samples);
  ProgressiveImage image = session.image();
  session.cancel();
  session.wait();
  return image.rgba;
}

std::vector<float> render_fresh(const Scene& scene, const RenderSettings& s) {
  ProgressiveSession session(std::make_shared<const Scene>(scene), s);
  return render(session, s.samples);
}

// A turn about z by `angle` around `pivot`, then a shift: what dragging and rotating a block does.
Transform turned(float angle, const Vec3& pivot, const Vec3& shift) {
  const float c = std::cos(angle), s = std::sin(angle);
  Transform t;
  t.m[0][0] = c, t.m[0][1] = -s;
  t.m[1][0] = s, t.m[1][1] = c;
  t.m[0][3] = pivot.x - (c * pivot.x - s * pivot.y) + shift.x;
  t.m[1][3] = pivot.y - (s * pivot.x + c * pivot.y) + shift.y;
  t.m[2][3] = shift.z;
  return t;
}

void expect_same_pixels(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  double mean = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(float)), 0)
        << "float " << i << ": " << a[i] << " vs " << b[i];
    mean += a[i];
  }
  EXPECT_GT(mean / a.size(), 0.01);  // not two black images
}

// Renders `scene`, moves instances `indices` to `to_world` on the shared resources, renders
// again, and compares with a scene built from scratch with the move. Returns what
// move_instances returned.
bool move_and_compare(Scene scene, const std::vector<uint32_t>& indices,
                      const std::vector<Transform>& to_world, IntegratorType type,
                      int expected_builds) {
  const RenderSettings s = settings(type);
  auto shared = std::make_shared<Scene>(scene);
  auto viewport = std::make_shared<ViewportScene>(shared, std::make_shared<BlasCache>());
  {
    ProgressiveSession before(viewport, s);
    const std::vector<float> image = render(before, s.samples);
    EXPECT_FALSE(image.empty());
  }
  EXPECT_EQ(viewport->builds(), 1);
  const bool in_place = viewport->move_instances(indices, to_world);
  ProgressiveSession after(viewport, s);
  const std::vector<float> moved = render(after, s.samples);
  EXPECT_EQ(viewport->builds(), expected_builds);

  for (size_t k = 0; k < indices.size(); ++k)
    scene.instances[indices[k]].object_to_world = to_world[k];
  expect_same_pixels(moved, render_fresh(scene, s));
  return in_place;
}

// A moved block: only the top level is rebuilt, photons are traced again on the moved scene,
// and the pixels are those of a scene built with the block where it now is.
TEST(ViewportScene, MovedInstanceRendersAsSceneBuiltWithTheMove) {
  const Transform move = turned(0.4f, Vec3(-0.3f, 0.2f, 0.0f), Vec3(0.25f, -0.15f, 0.05f));
  EXPECT_TRUE(move_and_compare(make_cornell_box(), {5}, {move}, IntegratorType::kPhotonMap, 1));
}

TEST(ViewportScene, MovedInstancesRayTraced) {
  const Transform a = turned(-0.3f, Vec3(0.4f, -0.3f, 0.0f), Vec3(-0.1f, 0.1f, 0.0f));
  const Transform b = Transform::translation(Vec3(0.05f, 0.0f, 0.3f));
  EXPECT_TRUE(move_and_compare(make_cornell_box(), {6, 5}, {a, b}, IntegratorType::kRayTrace, 1));
}

// An emissive panel moved far out: its world-space light triangles, the scene's bounds and the
// ray-offset length scale all change, and must be those of the moved scene.
TEST(ViewportScene, MovedEmitterAndBoundsMatchScratch) {
  Scene scene = make_cornell_box(20.0f);
  scene.materials.push_back(Material::emission(Vec3(4.0f, 3.0f, 2.0f), "panel"));
  add_mesh_instance(&scene, make_quad({-0.3f, 0.9f, 0.8f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.4f}),
                    static_cast<int32_t>(scene.materials.size() - 1));
  const uint32_t panel = static_cast<uint32_t>(scene.instances.size() - 1);
  const Transform out = turned(0.2f, Vec3(0.0f, 0.9f, 1.0f), Vec3(0.2f, -3.5f, 1.5f));
  EXPECT_TRUE(move_and_compare(scene, {panel}, {out}, IntegratorType::kPhotonMap, 1));
}

// A transform squashed flat cannot be traced (the Accel skips such instances): the resources
// are dropped and built again from the moved scene, which still renders as from scratch.
TEST(ViewportScene, UnusableTransformRebuilds) {
  Transform flat = Transform::translation(Vec3(0.0f, 0.0f, 0.1f));
  flat.m[2][2] = 0.0f;
  EXPECT_FALSE(move_and_compare(make_cornell_box(), {5}, {flat}, IntegratorType::kRayTrace, 2));
}

TEST(ViewportScene, RefusesMovesWhileRendering) {
  auto viewport = std::make_shared<ViewportScene>(std::make_shared<Scene>(make_cornell_box()),
                                                  std::make_shared<BlasCache>());
  RenderSettings s = settings(IntegratorType::kRayTrace);
  s.samples = 1 << 20;  // renders until cancelled
  ProgressiveSession session(viewport, s);
  session.start();
  ASSERT_GE(session.wait_for_samples(1, 60.0), 1);
  EXPECT_THROW(viewport->move_instances({5}, {Transform()}), std::runtime_error);
  session.cancel();
  session.wait();
  EXPECT_THROW(viewport->move_instances({99}, {Transform()}), std::out_of_range);
  EXPECT_TRUE(viewport->move_instances({5}, {Transform::translation(Vec3(0.1f, 0.0f, 0.0f))}));
}

// Edited materials on the shared resources: a recoloured wall and a panel whose emission is
// turned up (its light triangles and the emitters change) render as a scene built with the
// edits, without building the BVH again.
TEST(ViewportScene, EditedMaterialsRenderAsSceneBuiltWithThem) {
  Scene scene = make_cornell_box(20.0f);
  scene.materials.push_back(Material::emission(Vec3(1.0f, 1.0f, 1.0f), "panel"));
  const uint32_t panel = static_cast<uint32_t>(scene.materials.size() - 1);
  add_mesh_instance(&scene, make_quad({-0.3f, 0.9f, 0.8f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.4f}),
                    static_cast<int32_t>(panel));
  const RenderSettings s = settings(IntegratorType::kPhotonMap);
  auto viewport = std::make_shared<ViewportScene>(std::make_shared<Scene>(scene),
                                                  std::make_shared<BlasCache>());
  std::vector<float> before;
  {
    ProgressiveSession session(viewport, s);
    before = render(session, s.samples);
  }
  Material wall = Material::diffuse(Vec3(0.2f, 0.7f, 0.3f), scene.materials[0].name);
  Material brighter = Material::emission(Vec3(6.0f, 4.0f, 2.0f), "panel");
  EXPECT_TRUE(viewport->replace_material(0, wall));
  EXPECT_TRUE(viewport->replace_material(panel, brighter));
  ProgressiveSession session(viewport, s);
  const std::vector<float> edited = render(session, s.samples);
  EXPECT_EQ(viewport->builds(), 1);
  EXPECT_NE(edited, before);
  scene.materials[0] = wall;
  scene.materials[panel] = brighter;
  expect_same_pixels(edited, render_fresh(scene, s));
  Material bad = wall;
  bad.closures[0].params[0].texture = 3;  // the scene has no textures
  EXPECT_THROW(viewport->replace_material(0, bad), std::invalid_argument);
  EXPECT_THROW(viewport->replace_material(1000, wall), std::out_of_range);
}

}  // namespace
}  // namespace viewport_scene_test
}  // namespace photon

#include "photon/render/shadow_ray.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "photon/scene/material_params.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace shadow_ray_test {
namespace {

Material transparent(const Vec3& color, const std::string& name = "transparent") {
  Closure c;
  c.type = ClosureType::kTransparent;
  c.params = default_params(ClosureType::kTransparent);
  c[Param::kColor] = Input::constant(color);
  Material m;
  m.name = name;
  m.closures = {c};
  return m;
}

// A window as artists make one: Mix(Glass, Transparent) with factor `fac` on the Transparent.
Material window(float fac, const Vec3& color) {
  Material m = Material::glass(1.5f);
  m.closures[0].weight = {WeightFactor{Input::constant(fac), true}};
  Material t = transparent(color);
  t.closures[0].weight = {WeightFactor{Input::constant(fac), false}};
  m.closures.push_back(t.closures[0]);
  return m;
}

Material principled_alpha(float alpha) {
  Closure c;
  c.type = ClosureType::kPrincipled;
  c.params = default_params(ClosureType::kPrincipled);
  c[Param::kAlpha] = Input::constant(alpha);
  Material m;
  m.name = "leaf";
  m.closures = {c};
  return m;
}

// Panes of the given materials across the z axis at z = 1, 2, ...
Scene panes(const std::vector<Material>& materials) {
  Scene scene;
  for (size_t i = 0; i < materials.size(); ++i) {
    scene.materials.push_back(materials[i]);
    const float z = static_cast<float>(i + 1);
    add_mesh_instance(&scene, make_quad({-1, -1, z}, {2, 0, 0}, {0, 2, 0}),
                      static_cast<int32_t>(i));
  }
  return scene;
}

Ray up_to(float z) {
  Ray r;
  r.origin = Vec3(0.1f, -0.2f, 0.0f);
  r.direction = Vec3(0.0f, 0.0f, 1.0f);
  r.tmax = z;
  return r;
}

Vec3 through(const Scene& scene, float z = 100.0f, int crossings = kShadowCrossings) {
  std::vector<std::string> warnings;
  const Accel accel(scene, &warnings);
  return shadow_transmittance(accel, nullptr, up_to(z), crossings);
}

void expect_vec(const Vec3& got, const Vec3& want) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-6f) << "channel " << k;
}

TEST(ShadowRay, OpaqueScenesKeepTheAnyHitQuery) {
  std::vector<std::string> warnings;
  const Scene scene = panes({Material::diffuse(Vec3(0.5f)), Material::glass(1.5f)});
  const Accel accel(scene, &warnings);
  EXPECT_FALSE(accel.has_transparent_shadows());
  expect_vec(shadow_transmittance(accel, nullptr, up_to(100.0f)), Vec3(0.0f));
  expect_vec(shadow_transmittance(accel, nullptr, up_to(0.5f)), Vec3(1.0f));
}

TEST(ShadowRay, TransparentSurfacesPassTheirColour) {
  const Vec3 tint(0.5f, 0.25f, 1.0f);
  expect_vec(through(panes({transparent(tint)})), tint);
  // Two panes: the product, whatever their order along the ray.
  expect_vec(through(panes({transparent(tint), transparent(Vec3(0.5f))})), tint * 0.5f);
  // A shadow ray that ends before the second pane crosses only the first.
  expect_vec(through(panes({transparent(tint), Material::diffuse(Vec3(1.0f))}), 1.5f), tint);
  // An opaque surface behind (or before) a transparent one blocks the light.
  expect_vec(through(panes({transparent(tint), Material::diffuse(Vec3(1.0f))})), Vec3(0.0f));
  expect_vec(through(panes({Material::diffuse(Vec3(1.0f)), transparent(tint)})), Vec3(0.0f));
}

TEST(ShadowRay, WindowsAndAlphaPassTheirTransparentShare) {
  // Mix(Glass, Transparent 0.8) at 0.8: the Transparent closure weighs 0.64; the glass's
  // refraction bends light, so shadow rays do not take it.
  expect_vec(through(panes({window(0.8f, Vec3(0.8f))})), Vec3(0.64f));
  expect_vec(through(panes({principled_alpha(0.3f)})), Vec3(0.7f));
  expect_vec(through(panes({principled_alpha(1.0f)})), Vec3(0.0f));
  EXPECT_FALSE(principled_alpha(1.0f).may_be_transparent());
  EXPECT_FALSE(transparent(Vec3(0.0f)).may_be_transparent());
  EXPECT_TRUE(window(0.5f, Vec3(1.0f)).may_be_transparent());
  EXPECT_FALSE(window(0.0f, Vec3(1.0f)).may_be_transparent());
}

TEST(ShadowRay, CrossesAtMostTheLimitOfTransparentSurfaces) {
  const std::vector<Material> eight(8, transparent(Vec3(1.0f)));
  expect_vec(through(panes(eight), 100.0f, 8), Vec3(1.0f));
  expect_vec(through(panes(eight), 100.0f, 7), Vec3(0.0f));
  std::vector<Material> nine = eight;
  nine.push_back(transparent(Vec3(1.0f)));
  expect_vec(through(panes(nine)), Vec3(0.0f));
}

TEST(ShadowRay, ObjectsThatCastNoShadowsAreNotCrossed) {
  Scene scene = panes({transparent(Vec3(0.5f)), Material::diffuse(Vec3(1.0f))});
  scene.instances[1].visibility &= ~kVisibleShadow;
  expect_vec(through(scene), Vec3(0.5f));
  scene.instances[0].visibility &= ~kVisibleShadow;
  expect_vec(through(scene), Vec3(1.0f));
}

TEST(ShadowRay, EditedMaterialsUpdateTheShadowBits) {
  Scene scene = panes({Material::diffuse(Vec3(1.0f))});
  std::vector<std::string> warnings;
  Accel accel(scene, &warnings);
  expect_vec(shadow_transmittance(accel, nullptr, up_to(100.0f)), Vec3(0.0f));
  scene.materials[0] = transparent(Vec3(0.25f));
  accel.update_shadow_masks();
  EXPECT_TRUE(accel.has_transparent_shadows());
  expect_vec(shadow_transmittance(accel, nullptr, up_to(100.0f)), Vec3(0.25f));
  scene.materials[0] = Material::diffuse(Vec3(1.0f));
  accel.update_shadow_masks();
  EXPECT_FALSE(accel.has_transparent_shadows());
  expect_vec(shadow_transmittance(accel, nullptr, up_to(100.0f)), Vec3(0.0f));
}

TEST(ShadowRay, RayPastKeepsTheEndPoint) {
  SurfaceInteraction si;
  si.p = Vec3(0.1f, -0.2f, 1.0f);
  si.ng = Vec3(0.0f, 0.0f, -1.0f);
  const Ray r = up_to(3.0f);
  const Ray next = ray_past(r, si, 1.0f);
  EXPECT_GT(next.origin.z, 1.0f);
  EXPECT_NEAR(next.origin.z + next.tmax, 3.0f, 1e-6f);
  Ray open = r;
  open.tmax = INFINITY;
  EXPECT_EQ(ray_past(open, si, 1.0f).tmax, INFINITY);
}

}  // namespace
}  // namespace shadow_ray_test
}  // namespace photon

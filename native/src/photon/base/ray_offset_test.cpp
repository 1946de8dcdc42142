#include "photon/base/ray_offset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "photon/lights/lights.h"
#include "photon/render/accel.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace ray_offset_test {
namespace {

Material grey() {
  return Material::diffuse(Vec3(0.5f), "grey");
}

// Two parallel quads `scale` * 2 m wide, the lower at z = 0 and the upper `gap` * scale above,
// both moved by `offset`: the thin gap between a floor and a rug, at any scale.
Scene sandwich(float scale, float gap, const Vec3& offset) {
  Scene scene;
  scene.materials.push_back(grey());
  const Transform xf = Transform::translation(offset);
  add_mesh_instance(
      &scene, make_quad(Vec3(-1, -1, 0) * scale, Vec3(2, 0, 0) * scale, Vec3(0, 2, 0) * scale), 0,
      xf);
  add_mesh_instance(
      &scene, make_quad(Vec3(-1, -1, gap) * scale, Vec3(2, 0, 0) * scale, Vec3(0, 2, 0) * scale), 0,
      xf);
  return scene;
}

TEST(RayOffset, LeavesOnTheSideTheDirectionGoesTo) {
  const Vec3 p(0.3f, -0.2f, 0.0f), n(0, 0, 1);
  EXPECT_GT(offset_ray_origin(p, n, Vec3(0.1f, 0.0f, 0.5f), 1.0f).z, 0.0f);
  EXPECT_LT(offset_ray_origin(p, n, Vec3(0.1f, 0.0f, -0.5f), 1.0f).z, 0.0f);
  // Only the normal component moves.
  const Vec3 q = offset_ray_origin(p, n, Vec3(0, 0, 1), 1e-6f);
  EXPECT_EQ(q.x, p.x);
  EXPECT_EQ(q.y, p.y);
}

// Scenes of a metre or more keep the offset they had, bit for bit, so their images do not move.
TEST(RayOffset, MetreScaleScenesKeepTheFormerOffset) {
  EXPECT_EQ(scene_length_scale(Vec3(-1, -1, 0), Vec3(1, 1, 2)), 1.0f);
  EXPECT_EQ(scene_length_scale(Vec3(-500, -500, 0), Vec3(500, 500, 40)), 1.0f);
  const Vec3 n = normalize(Vec3(0.2f, -0.3f, 0.9f));
  for (const Vec3 p : {Vec3(0.0f), Vec3(0.7f, -1.3f, 0.01f), Vec3(120.0f, 3.0f, -8.0f)}) {
    const float former = 1e-4f * (1.0f + max_abs_component(p));
    const Vec3 q = offset_ray_origin(p, n, n, 1.0f);
    EXPECT_EQ(q.x, p.x + n.x * former);
    EXPECT_EQ(q.y, p.y + n.y * former);
    EXPECT_EQ(q.z, p.z + n.z * former);
  }
}

// The same scene at scales 1e-7 .. 1: the offset as a fraction of the scene's size stays within
// a small factor of the metre-scale one (the former absolute 1e-4 m floor was 1000x the size of a
// 1e-7 scene) and well above the float spacing at the hit point.
TEST(RayOffset, OffsetShrinksWithTheScene) {
  const Vec3 unit_p(0.4f, -0.7f, 0.0f), n(0, 0, 1);
  const Vec3 lo(-1, -1, 0), hi(1, 1, 1);
  const float unit_extent = length(hi - lo);
  const float unit_fraction =
      length(offset_ray_origin(unit_p, n, n, scene_length_scale(lo, hi)) - unit_p) / unit_extent;
  for (float scale : {1e-2f, 1e-4f, 1e-5f, 1e-6f, 1e-7f}) {
    const Vec3 p = unit_p * scale;
    const float ls = scene_length_scale(lo * scale, hi * scale);
    const float offset = length(offset_ray_origin(p, n, n, ls) - p);
    const float fraction = offset / (unit_extent * scale);
    EXPECT_LT(fraction, 10.0f * unit_fraction) << "scale " << scale;
    EXPECT_GT(fraction, 0.1f * unit_fraction) << "scale " << scale;
    EXPECT_GT(offset, 64.0f * max_abs_component(p) * std::numeric_limits<float>::epsilon())
        << "scale " << scale;
  }
}

// Rays spawned off the lower quad of a thin sandwich (gap 1% of its width) at every scale and at
// grazing angles neither re-hit their own quad nor jump over the upper one.
TEST(RayOffset, SpawnedRaysNeitherSelfIntersectNorSkipNearSurfaces) {
  for (float scale : {1e3f, 1.0f, 1e-3f, 1e-5f, 1e-7f}) {
    for (const Vec3 offset : {Vec3(0.0f), Vec3(3.0f, -2.0f, 1.0f) * scale}) {
      Scene scene = sandwich(scale, 0.02f, offset);
      std::vector<std::string> warnings;
      Accel accel(scene, &warnings);
      EXPECT_TRUE(warnings.empty()) << warnings.front();
      int skipped = 0, self_hits = 0;
      for (int i = 0; i < 256; ++i) {
        const Vec2 u((i + 0.5f) / 256.0f, std::fmod(i * 0.618034f, 1.0f));
        // A camera ray onto the lower quad from above, through the gap's edge region.
        const Vec3 target = offset + Vec3(1.8f * u.x - 0.9f, 1.8f * u.y - 0.9f, 0.0f) * scale;
        Ray down;
        down.direction = normalize(Vec3(0.3f, -0.2f, -1.0f));
        down.origin = target - down.direction * (0.01f * scale);
        Hit hit;
        if (!accel.intersect(down, kVisibleCamera, &hit)) continue;
        const SurfaceInteraction si = accel.interaction(hit);
        // Leave upwards, nearly along the surface, and hit the upper quad at once.
        const float cos_up = 0.05f + 0.9f * u.y;
        const Vec3 w = normalize(Vec3(std::sqrt(1.0f - cos_up * cos_up), 0.0f, cos_up));
        Ray up;
        up.origin = offset_ray_origin(si.p, si.ng, w, accel.length_scale());
        up.direction = w;
        if (up.origin.z - offset.z > 0.02f * scale) ++skipped;  // starts beyond the upper quad
        Hit next;
        if (!accel.intersect(up, kVisibleCamera, &next)) continue;  // left past the quad's edge
        const float height = (next.p.z - offset.z) / scale;
        if (height < 0.01f) ++self_hits;
      }
      EXPECT_EQ(self_hits, 0) << "scale " << scale << " offset " << offset.x;
      EXPECT_EQ(skipped, 0) << "scale " << scale << " offset " << offset.x;
    }
  }
}

TEST(RayOffset, WarnsWhenTheSceneLiesBeyondFloatPrecision) {
  EXPECT_FALSE(scene_beyond_float_precision(Vec3(-3, -3, 0), Vec3(3, 3, 3)));
  EXPECT_FALSE(scene_beyond_float_precision(Vec3(997, 997, 0), Vec3(1003, 1003, 3)));
  EXPECT_FALSE(scene_beyond_float_precision(Vec3(-3e-7f), Vec3(3e-7f)));
  EXPECT_TRUE(
      scene_beyond_float_precision(Vec3(1e7f - 3, 1e7f - 3, 0), Vec3(1e7f + 3, 1e7f + 3, 3)));

  std::vector<std::string> warnings;
  Scene far = sandwich(1.0f, 0.02f, Vec3(1e7f, 1e7f, 0.0f));
  Accel accel(far, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("from the origin"), std::string::npos) << warnings[0];
  warnings.clear();
  Scene near = sandwich(1.0f, 0.02f, Vec3(100.0f, 0.0f, 0.0f));
  Accel near_accel(near, &warnings);
  EXPECT_TRUE(warnings.empty());
}

// A 1 m square area light scaled by 1e-7 (area 1e-14 m^2) is still a light with the same power:
// an absolute 1e-12 m^2 area floor dropped it as "zero size".
TEST(RayOffset, TinyAreaLightOfATinySceneIsKept) {
  for (float scale : {1.0f, 1e-5f, 1e-7f}) {
    Light l;
    l.name = "tiny";
    l.type = LightType::kArea;
    l.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 2.0f * scale));
    l.size_x = l.size_y = scale;
    l.power = 10.0f;
    std::vector<std::string> warnings;
    LightSet set({l}, &warnings);
    ASSERT_EQ(set.size(), 1u) << "scale " << scale;
    EXPECT_TRUE(warnings.empty()) << warnings.front();
  }
  Light zero;
  zero.name = "flat";
  zero.type = LightType::kArea;
  zero.size_x = 0.0f;
  zero.size_y = 1.0f;
  zero.power = 10.0f;
  std::vector<std::string> warnings;
  EXPECT_EQ(LightSet({zero}, &warnings).size(), 0u);
  ASSERT_EQ(warnings.size(), 1u);
}

}  // namespace
}  // namespace ray_offset_test
}  // namespace photon

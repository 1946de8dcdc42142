// EmitterSet::intersect_lamps, which camera and glossy rays use to see lamp surfaces: in tree
// mode it tests only the lamps whose boxes the ray crosses, and must find exactly the lamp, the
// distance and the radiance the linear LightSet::intersect finds.
#include "photon/lights/emitter_set.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "photon/base/sampling.h"

namespace photon {
namespace emitter_set_test {
namespace {

std::vector<Light> random_lamps(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Light> lights;
  for (int i = 0; i < n; ++i) {
    Light l;
    l.name = "lamp";
    l.type = i % 3 == 1 ? LightType::kSpot : i % 3 == 2 ? LightType::kArea : LightType::kPoint;
    l.light_to_world =
        Transform::translation(Vec3(8.0f * u(rng) - 4.0f, 8.0f * u(rng) - 4.0f, 4.0f * u(rng)));
    l.color = Vec3(u(rng), u(rng), u(rng));
    l.power = 1.0f + 20.0f * u(rng);
    l.radius = 0.05f + 0.3f * u(rng);
    l.spot_size = 0.5f + u(rng);
    l.size_x = 0.2f + u(rng);
    l.size_y = 0.2f + u(rng);
    l.shape = i % 2 ? AreaShape::kEllipse : AreaShape::kRectangle;
    l.visibility = i % 5 == 0 ? kVisibleGlossy : kVisibleGlossy | kVisibleCamera;
    lights.push_back(l);
  }
  return lights;
}

TEST(EmitterSet, TreeLampIntersectionFindsWhatTheLinearSearchFinds) {
  std::vector<std::string> warnings;
  const LightSet lamps(random_lamps(300, 11), &warnings);
  const EmissiveMeshes no_meshes;
  const EmitterSet set(lamps, no_meshes, Vec3(0.0f));
  ASSERT_TRUE(set.use_tree());
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int hits = 0;
  for (int k = 0; k < 20000; ++k) {
    Ray ray;
    ray.origin = Vec3(10.0f * u(rng) - 5.0f, 10.0f * u(rng) - 5.0f, 5.0f * u(rng) - 0.5f);
    ray.direction = sample_uniform_sphere(Vec2(u(rng), u(rng)));
    ray.tmin = 0.0f;
    const float tmax = k % 2 ? INFINITY : 6.0f * u(rng);
    const uint32_t mask = k % 3 ? kVisibleCamera : kVisibleGlossy;
    float t_linear = -1.0f, t_tree = -2.0f;
    Vec3 le_linear(-1.0f), le_tree(-2.0f);
    const bool linear = lamps.intersect(ray, tmax, mask, &t_linear, &le_linear);
    const bool tree = set.intersect_lamps(ray, tmax, mask, &t_tree, &le_tree);
    ASSERT_EQ(linear, tree) << "ray " << k;
    if (!linear) continue;
    ++hits;
    EXPECT_EQ(t_linear, t_tree) << "ray " << k;
    EXPECT_EQ(le_linear.x, le_tree.x) << "ray " << k;
    EXPECT_EQ(le_linear.y, le_tree.y) << "ray " << k;
    EXPECT_EQ(le_linear.z, le_tree.z) << "ray " << k;
  }
  EXPECT_GT(hits, 1000);  // the rays do meet lamps: the comparison is not vacuous
}

}  // namespace
}  // namespace emitter_set_test
}  // namespace photon

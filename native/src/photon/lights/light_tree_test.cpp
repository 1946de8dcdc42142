// The light tree and the many-light direct lighting estimator built on it: the tree's pmf is the
// frequency with which it picks each emitter, emitters without power or with NaN bounds are
// never picked, and tree-sampled direct light has the mean of the every-light estimator.
#include "photon/lights/light_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "photon/lights/direct_lighting.h"
#include "photon/lights/emitter_set.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace light_tree_test {
namespace {

// Points, spots and one-sided quads of random power scattered under a ceiling.
std::vector<LightBounds> random_bounds(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<LightBounds> out;
  for (int i = 0; i < n; ++i) {
    LightBounds b;
    const Vec3 c(10.0f * u(rng) - 5.0f, 10.0f * u(rng) - 5.0f, 2.0f + u(rng));
    const float r = 0.2f * u(rng);
    b.lo = c - Vec3(r);
    b.hi = c + Vec3(r);
    b.power = 0.1f + 10.0f * u(rng);
    switch (i % 3) {
      case 0:  // point
        b.cos_theta_o = -1.0f;
        break;
      case 1:  // spot pointing roughly down
        b.axis = normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, -1.0f));
        b.cos_theta_o = 1.0f;
        b.cos_theta_e = std::cos(0.2f + u(rng));
        break;
      default:  // area light facing down
        b.axis = Vec3(0.0f, 0.0f, -1.0f);
        break;
    }
    out.push_back(b);
  }
  return out;
}

TEST(LightTree, PmfMatchesTheSamplingFrequency) {
  const std::vector<LightBounds> bounds = random_bounds(37, 5);
  const LightTree tree(bounds);
  ASSERT_EQ(tree.size(), bounds.size());
  const Vec3 points[] = {Vec3(0.0f, 0.0f, 0.0f), Vec3(4.0f, -3.0f, 2.5f), Vec3(-6.0f, 6.0f, 1.0f)};
  for (const Vec3& p : points) {
    constexpr int kN = 400000;
    std::vector<int> counts(bounds.size(), 0);
    int failed = 0;
    for (int k = 0; k < kN; ++k) {
      uint32_t index;
      float pmf;
      // A traversal can end where both children's (tighter) bounds rule p out: those emitters
      // cannot light p, and their pmf is 0.
      if (!tree.sample(p, (k + 0.5f) / kN, &index, &pmf)) {
        ++failed;
        continue;
      }
      ASSERT_LT(index, bounds.size());
      EXPECT_FLOAT_EQ(pmf, tree.pmf(p, index));
      ++counts[index];
    }
    double total = 0.0;
    for (uint32_t i = 0; i < bounds.size(); ++i) {
      const double pmf = tree.pmf(p, i);
      total += pmf;
      // Stratified u: the count is within a couple of strata of N * pmf per tree level.
      EXPECT_NEAR(counts[i] / double(kN), pmf, 64.0 / kN + 1e-6) << "emitter " << i;
    }
    EXPECT_LE(total, 1.0 + 1e-5);
    EXPECT_GT(total, 0.5);
    EXPECT_NEAR(failed / double(kN), 1.0 - total, 64.0 / kN + 1e-5);
  }
}

TEST(LightTree, ZeroPowerAndNaNEntriesAreNeverPicked) {
  std::vector<LightBounds> bounds = random_bounds(12, 9);
  bounds[2].power = 0.0f;
  bounds[5].power = NAN;
  bounds[7].lo.x = NAN;
  bounds[9].power = -3.0f;
  bounds[10].infinite = true;
  const LightTree tree(bounds);
  EXPECT_EQ(tree.size(), 7u);
  const Vec3 p(0.5f, 0.5f, 0.0f);
  for (uint32_t bad : {2u, 5u, 7u, 9u, 10u}) EXPECT_EQ(tree.pmf(p, bad), 0.0f);
  for (int k = 0; k < 10000; ++k) {
    uint32_t index;
    float pmf;
    if (!tree.sample(p, (k + 0.5f) / 10000, &index, &pmf)) continue;
    EXPECT_TRUE(index != 2 && index != 5 && index != 7 && index != 9 && index != 10);
    EXPECT_GT(pmf, 0.0f);
  }
  // Only bad entries: an empty tree that picks nothing.
  const LightTree none({bounds[2], bounds[5]});
  uint32_t index;
  float pmf;
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.sample(p, 0.5f, &index, &pmf));
}

TEST(LightTree, ClustersThatCannotReachAPointHaveNoImportance) {
  LightBounds spot;
  spot.lo = Vec3(-0.1f, -0.1f, 2.9f);
  spot.hi = Vec3(0.1f, 0.1f, 3.1f);
  spot.axis = Vec3(0.0f, 0.0f, -1.0f);  // straight down, 20 degree half angle
  spot.cos_theta_o = 1.0f;
  spot.cos_theta_e = std::cos(20.0f * kPi / 180.0f);
  spot.power = 1.0f;
  EXPECT_GT(LightTree::importance(Vec3(0.0f, 0.0f, 0.0f), spot), 0.0f);
  EXPECT_GT(LightTree::importance(Vec3(0.9f, 0.0f, 0.0f), spot), 0.0f);  // inside cone + box
  EXPECT_EQ(LightTree::importance(Vec3(3.0f, 0.0f, 0.0f), spot), 0.0f);  // far outside
  EXPECT_EQ(LightTree::importance(Vec3(0.0f, 0.0f, 5.0f), spot), 0.0f);  // behind
}

// A floor and a back wall lit by 60 lamps of every kind (points with and without radius,
// spots, areas), a sun, and an emissive quad split into triangles.
std::shared_ptr<Scene> many_light_scene() {
  auto scene = std::make_shared<Scene>();
  scene->materials.push_back(Material::diffuse(Vec3(0.6f)));
  scene->materials.push_back(Material::emission(Vec3(2.0f, 1.0f, 0.5f)));
  add_mesh_instance(scene.get(), make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  add_mesh_instance(scene.get(), make_quad({-5, 3, 0}, {10, 0, 0}, {0, 0, 3}), 0);
  // An occluder, so shadow rays matter.
  add_mesh_instance(scene.get(), make_box({-0.5f, -0.5f, 1.0f}, {0.5f, 0.5f, 1.2f}), 0);
  add_mesh_instance(scene.get(), make_quad({2, -2, 2.5f}, {0.5f, 0, 0}, {0, 0.5f, 0}), 1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 60; ++i) {
    Light l;
    l.name = "lamp";
    l.type = i % 4 == 2 ? LightType::kSpot : i % 4 == 3 ? LightType::kArea : LightType::kPoint;
    l.light_to_world =
        Transform::translation(Vec3(8.0f * u(rng) - 4.0f, 6.0f * u(rng) - 4.0f, 1.5f + u(rng)));
    l.color = Vec3(u(rng), u(rng), u(rng));
    l.power = 1.0f + 20.0f * u(rng);
    l.radius = i % 4 == 0 ? 0.0f : 0.1f * u(rng);
    l.spot_size = 0.5f + u(rng);
    l.size_x = l.size_y = 0.3f;
    scene->lights.push_back(l);
  }
  Light sun;
  sun.type = LightType::kSun;
  sun.power = 0.5f;
  sun.sun_angle = 0.1f;
  sun.light_to_world = Transform::translation(Vec3(0.0f));
  scene->lights.push_back(sun);
  return scene;
}

struct Estimate {
  double mean[3] = {0, 0, 0}, standard_error[3] = {0, 0, 0};
};

Estimate estimate(const RenderContext& context, const SurfaceInteraction& si, int n) {
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(17, 5, static_cast<uint32_t>(i), static_cast<uint32_t>(n));
    const Vec3 e = direct_irradiance(context, si, sampler);
    const double v[3] = {e.x, e.y, e.z};
    for (int c = 0; c < 3; ++c) {
      sum[c] += v[c];
      sum2[c] += v[c] * v[c];
    }
  }
  Estimate out;
  for (int c = 0; c < 3; ++c) {
    out.mean[c] = sum[c] / n;
    out.standard_error[c] = std::sqrt(std::max(0.0, sum2[c] / n - out.mean[c] * out.mean[c]) / n);
  }
  return out;
}

TEST(LightTreeDirectLighting, MatchesTheEveryLightEstimator) {
  const std::shared_ptr<Scene> scene = many_light_scene();
  RenderSettings settings;
  const SceneResources resources(*scene, settings, nullptr);
  ASSERT_TRUE(resources.emitters().use_tree());  // 61 lamps + the emissive quad
  const EmitterSet every(resources.lights(), resources.emissive(), scene->world.color,
                         static_cast<size_t>(-1));
  ASSERT_FALSE(every.use_tree());
  RenderContext every_context = resources.context();
  every_context.emitters = &every;

  struct Point {
    Vec3 p, n;
  };
  const Point points[] = {{{0.0f, 0.0f, 0.0f}, {0, 0, 1}},    // under the occluder
                          {{2.5f, -1.0f, 0.0f}, {0, 0, 1}},   // near the emissive quad
                          {{-3.0f, 3.0f, 1.0f}, {0, -1, 0}},  // on the back wall
                          {{4.0f, -4.0f, 0.0f}, {0, 0, 1}}};
  for (const Point& pt : points) {
    SurfaceInteraction si;
    si.p = pt.p;
    si.ng = si.ns = pt.n;
    si.mat = &scene->materials[0];
    si.material = 0;
    const Estimate tree = estimate(resources.context(), si, 60000);
    const Estimate all = estimate(every_context, si, 6000);
    for (int c = 0; c < 3; ++c) {
      const double se = std::hypot(tree.standard_error[c], all.standard_error[c]);
      EXPECT_NEAR(tree.mean[c], all.mean[c], 5.0 * se + 1e-4 * all.mean[c])
          << "point (" << pt.p.x << ", " << pt.p.y << ", " << pt.p.z << ") channel " << c
          << ": tree " << tree.mean[c] << " +- " << tree.standard_error[c] << ", every light "
          << all.mean[c] << " +- " << all.standard_error[c];
    }
  }
}

}  // namespace
}  // namespace light_tree_test
}  // namespace photon

// The shared path walker (path_walker.h): Russian roulette keeps the estimator unbiased, the
// depth limit and the specular-chain rule hold, and irradiance-cache placement visits exactly
// the points the camera walk final-gathers at.
#include "photon/integrators/path_walker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "photon/base/sampling.h"
#include "photon/integrators/camera_path.h"
#include "photon/integrators/photon_map/irradiance_cache_build.h"
#include "photon/scene/camera.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace path_walker_test {
namespace {

struct Fixture {
  explicit Fixture(Scene s, int max_depth = 8)
      : scene(std::move(s)),
        settings(make_settings(max_depth)),
        resources(scene, settings, &warnings),
        context(resources.context()) {}
  static RenderSettings make_settings(int max_depth) {
    RenderSettings r;
    r.full_width = r.full_height = 32;
    r.x1 = r.y1 = 32;
    r.max_depth = max_depth;
    return r;
  }
  Scene scene;
  std::vector<std::string> warnings;
  RenderSettings settings;
  SceneResources resources;
  const RenderContext& context;
};

// Records the throughput at every vertex and what happened after it.
struct RecordingVisitor {
  const RenderContext& context;
  ShadingPoint sp{};
  std::vector<int> depths;
  std::vector<Vec3> throughputs;
  std::vector<uint32_t> masks;
  std::vector<bool> continued;

  bool segment(const PathState&, bool found, const Hit&) { return found; }
  VertexStep vertex(PathState& state, const Hit&, const SurfaceInteraction& si) {
    depths.push_back(state.depth);
    throughputs.push_back(state.throughput);
    masks.push_back(state.mask);
    sp = shade(context, si, -state.ray.direction);
    return VertexStep::scatter(sp.bsdf);
  }
  void scattered(const PathState&, bool continues) { continued.push_back(continues); }
};

RecordingVisitor walk(const Fixture& f, const PathRules& rules, const Ray& ray, uint32_t mask,
                      Sampler& sampler) {
  RecordingVisitor v{f.context};
  PathState state;
  state.ray = ray;
  state.mask = mask;
  walk_path(f.context, rules, &state, sampler, v);
  return v;
}

// The inside of a closed mirror sphere: every path bounces until the walker ends it.
Scene mirror_sphere(const Vec3& tint) {
  Scene scene;
  scene.materials.push_back(Material::mirror(tint));
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0}, 1.0f, 48, 24), 0);
  return scene;
}

Ray ray_from_centre(Sampler& sampler) {
  Ray r;
  r.origin = Vec3(0.0f);
  r.direction = sample_uniform_sphere(sampler.get_2d());
  return r;
}

// A furnace for the roulette: the mean throughput arriving at each depth (0 for a path the
// roulette ended) must equal the throughput without roulette, within 5 standard errors.
void expect_unbiased(const PathRules& rules) {
  const Fixture f(mirror_sphere({0.9f, 0.7f, 0.5f}));
  const int depths = rules.max_depth + 1;
  constexpr int kPaths = 60000;
  std::vector<double> sum(3 * depths, 0.0), sum2(3 * depths, 0.0), exact(3 * depths, 0.0);
  int deepest = 0, reached_last = 0;
  PathRules plain = rules;
  plain.roulette = Roulette::kNone;
  for (int i = 0; i < kPaths; ++i) {
    Sampler a(7, 1, static_cast<uint32_t>(i), kPaths);
    const RecordingVisitor v = walk(f, rules, ray_from_centre(a), kVisibleDiffuse, a);
    for (size_t k = 0; k < v.depths.size(); ++k) {
      const int d = v.depths[k];
      deepest = std::max(deepest, d);
      if (d == rules.max_depth) ++reached_last;
      const float c[3] = {v.throughputs[k].x, v.throughputs[k].y, v.throughputs[k].z};
      for (int ch = 0; ch < 3; ++ch) sum[3 * d + ch] += c[ch], sum2[3 * d + ch] += c[ch] * c[ch];
    }
    Sampler b(7, 1, static_cast<uint32_t>(i), kPaths);
    const RecordingVisitor w = walk(f, plain, ray_from_centre(b), kVisibleDiffuse, b);
    ASSERT_EQ(w.depths.size(), static_cast<size_t>(depths)) << "paths without roulette go on";
    for (size_t k = 0; k < w.depths.size(); ++k) {
      const float c[3] = {w.throughputs[k].x, w.throughputs[k].y, w.throughputs[k].z};
      for (int ch = 0; ch < 3; ++ch) exact[3 * w.depths[k] + ch] += c[ch];
    }
  }
  EXPECT_EQ(deepest, rules.max_depth);
  // The roulette really ended paths (else the test proves nothing).
  EXPECT_LT(reached_last, kPaths * 3 / 4);
  for (int d = 0; d < depths; ++d)
    for (int ch = 0; ch < 3; ++ch) {
      const double mean = sum[3 * d + ch] / kPaths, want = exact[3 * d + ch] / kPaths;
      const double var = sum2[3 * d + ch] / kPaths - mean * mean;
      const double se = std::sqrt(std::max(var, 0.0) / kPaths);
      EXPECT_NEAR(mean, want, 5.0 * se + 1e-6 * want) << "depth " << d << " channel " << ch;
    }
}

TEST(PathWalker, PathThroughputRouletteIsUnbiased) {
  PathRules rules = importance_rules(10);
  expect_unbiased(rules);
}

TEST(PathWalker, BounceAlbedoRouletteIsUnbiased) {
  expect_unbiased(power_rules(10, kLobeAll));
}

TEST(PathWalker, MaxDepthEndsThePath) {
  const Fixture f(mirror_sphere(Vec3(1.0f)));
  for (int max_depth : {0, 1, 3, 6}) {
    PathRules rules = importance_rules(max_depth);
    rules.roulette = Roulette::kNone;
    Sampler sampler(3, 0, 0);
    const RecordingVisitor v = walk(f, rules, ray_from_centre(sampler), kVisibleCamera, sampler);
    ASSERT_EQ(v.depths.size(), static_cast<size_t>(max_depth + 1));
    for (int d = 0; d <= max_depth; ++d) {
      EXPECT_EQ(v.depths[d], d);
      EXPECT_EQ(v.continued[d], d < max_depth) << "depth " << d << " of " << max_depth;
    }
  }
}

// A diffuse sphere ends camera and gather chains (glossy and specular lobes only) and caustic
// photons (delta lobes only), while global photons go on through it.
TEST(PathWalker, SpecularChainContinuesThroughItsLobesOnly) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0}, 1.0f, 48, 24), 0);
  const Fixture f(std::move(scene));
  int global_continued = 0;
  for (int i = 0; i < 64; ++i) {
    for (const PathRules& rules : {importance_rules(8), power_rules(8, kLobeSpecular)}) {
      Sampler s(5, 0, static_cast<uint32_t>(i));
      const RecordingVisitor v = walk(f, rules, ray_from_centre(s), kVisibleCamera, s);
      ASSERT_EQ(v.depths.size(), 1u);
      EXPECT_FALSE(v.continued[0]);
    }
    Sampler s(5, 0, static_cast<uint32_t>(i));
    const RecordingVisitor v =
        walk(f, power_rules(8, kLobeAll), ray_from_centre(s), kVisibleDiffuse, s);
    if (v.depths.size() > 1) ++global_continued;
  }
  EXPECT_GT(global_continued, 32);
}

// Camera rays stay camera rays through a Transparent BSDF (Cycles' transparent bounces); a
// gather ray through it becomes a transmission ray.
TEST(PathWalker, TransparentKeepsCameraVisibilityOnCameraPathsOnly) {
  Scene scene;
  Closure c;
  c.type = ClosureType::kTransparent;
  c[Param::kColor] = Input::constant(1.0f);
  scene.materials.push_back(Material{"transparent", {c}});
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_quad({-5, -5, 1}, {10, 0, 0}, {0, 10, 0}), 0);
  add_mesh_instance(&scene, make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 1);
  const Fixture f(std::move(scene));
  Ray down;
  down.origin = Vec3(0.1f, 0.2f, 2.0f);
  down.direction = Vec3(0, 0, -1);
  Sampler s1(1, 0, 0), s2(1, 0, 0);
  const RecordingVisitor camera =
      walk(f, camera_render_walk(f.context).rules, down, kVisibleCamera, s1);
  ASSERT_GE(camera.masks.size(), 2u);
  EXPECT_EQ(camera.masks[1], kVisibleCamera);
  const RecordingVisitor gather = walk(f, importance_rules(8), down, kVisibleDiffuse, s2);
  ASSERT_GE(gather.masks.size(), 2u);
  EXPECT_EQ(gather.masks[1], kVisibleTransmission);
}

// A room with a mirror, a Transparent pane, a shadow catcher and a surface held out by a Holdout
// closure (it still has a diffuse lobe): the camera meets mattes and specular chains.
Scene matte_room() {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.6f)));  // 0 floor, walls
  scene.materials.push_back(Material::mirror(Vec3(1.0f)));   // 1
  Closure t;
  t.type = ClosureType::kTransparent;
  t[Param::kColor] = Input::constant(1.0f);
  scene.materials.push_back(Material{"transparent", {t}});  // 2
  Closure h;
  h.type = ClosureType::kHoldout;
  Material held = Material::diffuse(Vec3(0.7f));
  held.closures.push_back(h);
  scene.materials.push_back(held);  // 3 holdout + diffuse
  add_mesh_instance(&scene, make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  add_mesh_instance(&scene, make_quad({-5, 3, 0}, {10, 0, 0}, {0, 0, 4}), 0);
  add_mesh_instance(&scene, make_quad({-2.0f, 1.5f, 0}, {1.8f, -0.6f, 0}, {0, 0, 2}), 1);
  add_mesh_instance(&scene, make_quad({0.3f, 0.0f, 0}, {1.2f, 0, 0}, {0, 0, 1.2f}), 2);
  add_mesh_instance(&scene, make_box({0.5f, 0.5f, 0}, {1.1f, 1.1f, 0.6f}), 0);
  add_mesh_instance(&scene, make_quad({-1.3f, -0.6f, 0}, {1.0f, 0, 0}, {0, 0, 0.9f}), 3);
  add_mesh_instance(&scene, make_quad({1.4f, -1.6f, 0.3f}, {0.8f, 0, 0}, {0, 0.8f, 0}), 0);
  scene.instances.back().shadow_catcher = true;
  Light sun;
  sun.type = LightType::kSun;
  sun.power = 3.0f;
  scene.lights.push_back(sun);
  scene.camera = make_look_at_camera({0.0f, -4.0f, 1.6f}, {0.0f, 0.5f, 0.5f}, 0.9f, 1.0f);
  return scene;
}

struct Point {
  int depth;
  Vec3 p;
};

// The cache walk and the camera walk final-gather at the same points. Paths meet only
// deterministic lobes (a white mirror, a Transparent pane), so the two samplers do not matter.
TEST(PathWalker, CachePlacementVisitsTheCameraWalksGatherPoints) {
  const Fixture f(matte_room());
  const int n = f.settings.full_width;
  int total = 0, via_chain = 0;
  for (int py = 0; py < n; ++py)
    for (int px = 0; px < n; ++px) {
      const Ray ray =
          generate_camera_ray(f.scene.camera, (px + 0.5f) / n, (py + 0.5f) / n, Vec2(0.5f, 0.5f));
      std::vector<Point> camera, cache;
      CameraHit first;
      first.found = f.context.accel->intersect(ray, kVisibleCamera, &first.hit);
      Sampler camera_sampler(11, static_cast<uint64_t>(py * n + px), 0);
      RadianceSample result;
      trace_camera_path(
          f.context, ray, first, camera_sampler,
          [&](const PathVertex& v, RadianceSample*) {
            // Where PhotonMapIntegrator::shade_diffuse final-gathers.
            if (!v.after_glossy && !is_black(v.throughput * v.shading->bsdf.diffuse_reflectance()))
              camera.push_back({v.depth, v.si->p});
          },
          &result);
      Sampler cache_sampler(12, static_cast<uint64_t>(py * n + px), 0);
      visit_cache_candidates(f.context, ray, cache_sampler, [&](const PathVertex& v) {
        cache.push_back({v.depth, v.si->p});
      });
      ASSERT_EQ(camera.size(), cache.size()) << "pixel " << px << ", " << py;
      for (size_t i = 0; i < camera.size(); ++i) {
        EXPECT_EQ(camera[i].depth, cache[i].depth);
        EXPECT_EQ(camera[i].p.x, cache[i].p.x);
        EXPECT_EQ(camera[i].p.y, cache[i].p.y);
        EXPECT_EQ(camera[i].p.z, cache[i].p.z);
      }
      total += static_cast<int>(camera.size());
      for (const Point& q : camera) via_chain += q.depth > 0;
    }
  // The scene exercises what it is for: gathers directly and behind mirrors, panes and
  // catchers.
  EXPECT_GT(total, n * n / 2);
  EXPECT_GT(via_chain, n * n / 20);
}

}  // namespace
}  // namespace path_walker_test
}  // namespace photon

// The Light Path node's depths along a walk (camera_shade_ray over the walker's PathState):
// bounces are counted by kind as Cycles counts them, and Ray Depth leaves out straight
// pass-throughs of a Transparent BSDF.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "photon/base/sampling.h"
#include "photon/integrators/camera_path.h"
#include "photon/integrators/path_walker.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace light_path_depth_test {
namespace {

struct Fixture {
  explicit Fixture(Scene s) : scene(std::move(s)), resources(scene, settings(), &warnings) {}
  static RenderSettings settings() {
    RenderSettings r;
    r.full_width = r.full_height = r.x1 = r.y1 = 8;
    r.max_depth = 8;
    return r;
  }
  Scene scene;
  std::vector<std::string> warnings;
  SceneResources resources;
};

// The Light Path view at every vertex of one walk.
struct DepthVisitor {
  const RenderContext& context;
  ShadingPoint sp{};
  std::vector<ShadeRay> rays;

  bool segment(const PathState&, bool found, const Hit&) { return found; }
  VertexStep vertex(PathState& state, const Hit&, const SurfaceInteraction& si) {
    rays.push_back(camera_shade_ray(state, 0.0f));
    sp = shade(context, si, -state.ray.direction);
    return VertexStep::scatter(sp.bsdf);
  }
  void scattered(const PathState&, bool) {}
};

std::vector<ShadeRay> walk(const Fixture& f, const PathRules& rules, const Ray& ray,
                           uint32_t seed) {
  DepthVisitor v{f.resources.context()};
  PathState state;
  state.ray = ray;
  Sampler sampler(seed, 0, 0);
  walk_path(f.resources.context(), rules, &state, sampler, v);
  return v.rays;
}

PathRules endless_rules(uint8_t lobes = kLobeAll) {
  PathRules rules = importance_rules(6);
  rules.roulette = Roulette::kNone;
  rules.continue_lobes = lobes;
  return rules;
}

Ray from_centre(uint32_t i) {
  Sampler s(11, 0, i);
  Ray r;
  r.origin = Vec3(0.0f);
  r.direction = sample_uniform_sphere(s.get_2d());
  return r;
}

Scene sphere_of(Material m) {
  Scene scene;
  scene.materials.push_back(std::move(m));
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0}, 1.0f, 48, 24), 0);
  return scene;
}

TEST(LightPathDepth, MirrorBouncesAreGlossyAndDiffuseOnesDiffuse) {
  const Fixture mirror(sphere_of(Material::mirror(Vec3(1.0f))));
  const Fixture diffuse(sphere_of(Material::diffuse(Vec3(0.9f))));
  for (uint32_t i = 0; i < 8; ++i) {
    const std::vector<ShadeRay> m = walk(mirror, endless_rules(), from_centre(i), i);
    ASSERT_EQ(m.size(), 7u);
    const std::vector<ShadeRay> d = walk(diffuse, endless_rules(), from_centre(i), i);
    ASSERT_EQ(d.size(), 7u);
    for (uint16_t k = 0; k < 7; ++k) {
      EXPECT_EQ(m[k].depth, k);
      EXPECT_EQ(m[k].glossy_depth, k);
      EXPECT_EQ(m[k].diffuse_depth + m[k].transmission_depth + m[k].transparent_depth, 0);
      EXPECT_EQ(d[k].depth, k);
      EXPECT_EQ(d[k].diffuse_depth, k);
      EXPECT_EQ(d[k].glossy_depth + d[k].transmission_depth + d[k].transparent_depth, 0);
    }
  }
}

// Inside a glass sphere every bounce is a Fresnel reflection (glossy) or a refraction out; the
// escaped paths end, so each walk is reflections then at most one transmission.
TEST(LightPathDepth, GlassSplitsIntoGlossyAndTransmission) {
  Scene scene = sphere_of(Material::glass(1.5f));
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0}, 3.0f, 48, 24), 1);  // a room around it
  const Fixture f(std::move(scene));
  int transmitted = 0;
  for (uint32_t i = 0; i < 32; ++i) {
    const std::vector<ShadeRay> r = walk(f, endless_rules(), from_centre(i), i);
    for (size_t k = 0; k < r.size(); ++k) {
      EXPECT_EQ(r[k].depth, k);
      EXPECT_EQ(r[k].glossy_depth + r[k].transmission_depth + r[k].diffuse_depth, r[k].depth);
      EXPECT_EQ(r[k].transparent_depth, 0);
      if (k > 0 && r[k].transmission_depth > r[k - 1].transmission_depth) ++transmitted;
    }
  }
  EXPECT_GT(transmitted, 16);  // most rays leave the glass at the first interface
}

// A camera ray through a Transparent pane onto a diffuse floor: one transparent bounce, which
// Ray Depth does not count; the bounce off the floor back up through the pane counts as diffuse.
TEST(LightPathDepth, TransparentBouncesAreLeftOutOfRayDepth) {
  Scene scene;
  Closure c;
  c.type = ClosureType::kTransparent;
  c[Param::kColor] = Input::constant(1.0f);
  scene.materials.push_back(Material{"transparent", {c}});
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_quad({-50, -50, 1}, {100, 0, 0}, {0, 100, 0}), 0);
  add_mesh_instance(&scene, make_quad({-50, -50, 0}, {100, 0, 0}, {0, 100, 0}), 1);
  const Fixture f(std::move(scene));
  Ray down;
  down.origin = Vec3(0.1f, 0.2f, 2.0f);
  down.direction = Vec3(0, 0, -1);
  PathRules rules = endless_rules();
  rules.transparent_keeps_visibility = true;
  const std::vector<ShadeRay> r = walk(f, rules, down, 3);
  ASSERT_GE(r.size(), 3u);  // pane, floor, pane from below (then the sky)
  EXPECT_EQ(r[0].depth, 0);
  EXPECT_EQ(r[1].depth, 0);
  EXPECT_EQ(r[1].transparent_depth, 1);
  EXPECT_EQ(r[1].flags, kRayCamera);  // still a camera ray behind the pane
  EXPECT_EQ(r[2].depth, 1);
  EXPECT_EQ(r[2].diffuse_depth, 1);
  EXPECT_EQ(r[2].transparent_depth, 1);
}

}  // namespace
}  // namespace light_path_depth_test
}  // namespace photon

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>

#include "photon/integrators/sppm/photon_kdtree.h"
#include "photon/integrators/sppm/sppm_camera.h"
#include "photon/integrators/sppm/sppm_integrator.h"
#include "photon/session/progressive_session.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace sppm_test {
namespace {

RenderSettings sppm_settings(int size, int iterations, uint64_t photons) {
  RenderSettings s;
  s.full_width = s.full_height = size;
  s.x1 = s.y1 = size;
  s.seed = 5;
  s.integrator = IntegratorType::kSppm;
  s.sppm_iterations = iterations;
  s.sppm_photons_per_iteration = photons;
  return s;
}

struct Rendered {
  std::vector<float> rgba;
  RenderStats stats;
  std::vector<Tile> tiles;
};

Rendered render(const Scene& scene, const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  return {session.image(), session.stats(), session.take_tiles(0.0)};
}

double mean_channel(const std::vector<float>& rgba, int c) {
  double sum = 0.0;
  for (size_t i = c; i < rgba.size(); i += 4) sum += rgba[i];
  return sum / (rgba.size() / 4);
}

double rms_error(const std::vector<float>& rgba, double expected) {
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += (rgba[i] - expected) * (rgba[i] - expected);
  return std::sqrt(sum / (rgba.size() / 4));
}

// A closed box whose walls emit Le and reflect albedo rho: L = Le / (1 - rho) everywhere.
Scene emissive_furnace(float rho, float le) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(rho)).with_emission(Vec3(le)));
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  scene.camera = make_look_at_camera({0, -0.5f, 0}, {0, 1, 0.2f}, 1.2f, 1.0f);
  return scene;
}

TEST(Sppm, EmissiveFurnaceConvergesToLeOverOneMinusAlbedo) {
  const Rendered r = render(emissive_furnace(0.6f, 1.0f), sppm_settings(24, 16, 20000));
  EXPECT_EQ(r.stats.iterations.iterations, 16);
  EXPECT_NEAR(mean_channel(r.rgba, 0), 1.0 / (1.0 - 0.6), 0.02 * 2.5);
  EXPECT_NEAR(mean_channel(r.rgba, 2), 1.0 / (1.0 - 0.6), 0.02 * 2.5);
  EXPECT_NEAR(mean_channel(r.rgba, 3), 1.0, 1e-6);
}

TEST(Sppm, FurnaceErrorFallsWithIterations) {
  // Uniform radiance: the density estimate has no blur bias here, so the error is noise, which
  // the iterations average away.
  const Scene scene = emissive_furnace(0.8f, 1.0f);
  const double expected = 1.0 / (1.0 - 0.8);
  const double few = rms_error(render(scene, sppm_settings(24, 2, 5000)).rgba, expected);
  const double many = rms_error(render(scene, sppm_settings(24, 32, 5000)).rgba, expected);
  EXPECT_LT(many, 0.5 * few) << "2 iterations: " << few << ", 32: " << many;
}

// A diffuse plane under a point light of intensity I at height h: E = I cos(theta) / d^2 and no
// indirect light.
TEST(Sppm, PlaneUnderPointLightMatchesInverseSquareLaw) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 0);
  Light light;
  light.type = LightType::kPoint;
  light.power = 100.0f;
  const float h = 1.0f;
  light.light_to_world = Transform::translation(Vec3(0, 0, h));
  scene.lights.push_back(light);
  scene.camera.projection = Projection::kOrthographic;
  scene.camera.set_camera_to_world(Transform::translation(Vec3(0, 0, 3)));
  scene.camera.window_min_x = scene.camera.window_min_y = -0.33f;
  scene.camera.window_max_x = scene.camera.window_max_y = 0.33f;
  const Rendered r = render(scene, sppm_settings(33, 16, 2000));
  const double intensity = 100.0 / (4.0 * kPi);
  auto pixel = [&](int x, int y) { return r.rgba[(static_cast<size_t>(y) * 33 + x) * 4]; };
  EXPECT_NEAR(pixel(16, 16), 0.5 / kPi * intensity / (h * h), 0.01 * 0.5 / kPi * intensity);
  const double rr = 0.3, d2 = h * h + rr * rr;
  const double expected = 0.5 / kPi * intensity * (h / std::sqrt(d2)) / d2;
  for (auto [x, y] : {std::pair{1, 16}, std::pair{31, 16}, std::pair{16, 1}, std::pair{16, 31}})
    EXPECT_NEAR(pixel(x, y), expected, 0.01 * expected) << x << "," << y;
}

TEST(Sppm, ImageIsTheSameForAnyThreadCountAndTileSize) {
  const Scene scene = make_caustic_box();
  RenderSettings s = sppm_settings(32, 3, 20000);
  s.light_passes = true;
  std::vector<float> reference;
  for (auto [threads, tile] : {std::pair{1, 64}, std::pair{2, 8}, std::pair{3, 5}}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    s.threads = threads;
    s.tile_size = tile;
    const Rendered r = render(scene, s);
    EXPECT_GT(mean_channel(r.rgba, 0), 0.01);
    if (reference.empty())
      reference = r.rgba;
    else
      EXPECT_EQ(r.rgba, reference) << threads << " threads, tiles of " << tile;
  }
}

TEST(Sppm, CornellBoxMeanMatchesPhotonMapping) {
  const Scene scene = make_cornell_box();
  RenderSettings s = sppm_settings(32, 32, 50000);
  const Rendered sppm = render(scene, s);
  s.integrator = IntegratorType::kPhotonMap;
  s.samples = 32;
  s.photons = 200000;
  const Rendered pm = render(scene, s);
  for (int c = 0; c < 3; ++c) {
    const double a = mean_channel(sppm.rgba, c), b = mean_channel(pm.rgba, c);
    EXPECT_NEAR(a, b, 0.03 * b) << "channel " << c;
  }
}

// A glass ball over a diffuse 2 m floor, seen from the side just under the ball, lit by an
// emissive quad above it or by a uniform world. Shadow rays stop at glass, so the floor the ball
// shadows is lit only through the glass: by caustics (L S+ D), which only photons carry.
Scene glass_ball_over_floor(bool world_light, float ior, bool ball = true) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0);
  scene.materials.push_back(Material::glass(ior));
  if (ball) add_mesh_instance(&scene, make_uv_sphere({0, 0, 0.5f}, 0.3f, 64, 32), 1);
  if (world_light) {
    scene.world = World::uniform(Vec3(1.0f));
  } else {
    scene.materials.push_back(Material::emission(Vec3(40.0f)));
    add_mesh_instance(&scene, make_quad({-0.2f, -0.2f, 2.0f}, {0, 0.4f, 0}, {0.4f, 0, 0}),
                      static_cast<int32_t>(scene.materials.size() - 1));
  }
  scene.camera = make_look_at_camera({0, -2, 1}, {0, 0, 0}, 0.06f, 1.0f);
  return scene;
}

TEST(Sppm, LightThroughAnInvisibleGlassBallArrivesExactlyAsPhotons) {
  // Glass of IOR 1 bends and reflects nothing: the floor is lit as if the ball were not there
  // (ray tracing without it gives that exactly), but under the ball only by photons that
  // passed through it. From the world and from an emissive mesh.
  for (const bool world : {true, false}) {
    RenderSettings s = sppm_settings(16, 32, 50000);
    const double sppm = mean_channel(render(glass_ball_over_floor(world, 1.0f), s).rgba, 0);
    s.integrator = IntegratorType::kRayTrace;
    s.samples = 64;
    const double shadowed = mean_channel(render(glass_ball_over_floor(world, 1.0f), s).rgba, 0);
    const double open = mean_channel(render(glass_ball_over_floor(world, 1.0f, false), s).rgba, 0);
    if (world) EXPECT_NEAR(open, 0.8, 1e-4);  // albedo times the world's radiance
    EXPECT_NEAR(sppm, open, 0.03 * open) << (world ? "world" : "emissive quad");
    EXPECT_LT(shadowed, 0.8 * open) << "the ball must shadow the floor the camera sees";
  }
}

TEST(Sppm, CausticOfAnEmissiveMeshMatchesPhotonMapping) {
  const Scene scene = glass_ball_over_floor(false, 1.5f);
  RenderSettings s = sppm_settings(16, 32, 50000);
  const double sppm = mean_channel(render(scene, s).rgba, 0);
  s.integrator = IntegratorType::kPhotonMap;
  s.samples = 16;
  s.photons = 50000;
  s.caustic_photons = 400000;
  const double pm = mean_channel(render(scene, s).rgba, 0);
  EXPECT_NEAR(sppm, pm, 0.03 * pm);
}

TEST(Sppm, EveryCompleteIterationReachesTheResultAndCancelKeepsTheLast) {
  const Scene scene = make_cornell_box();
  RenderSettings s = sppm_settings(16, 1000000, 2000);
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  std::vector<Tile> tiles;
  while (tiles.empty()) {
    tiles = session.take_tiles(5.0);
    ASSERT_FALSE(session.finished() && tiles.empty());
  }
  session.cancel();
  session.wait();
  for (Tile& t : session.take_tiles(0.0)) tiles.push_back(std::move(t));
  ASSERT_FALSE(tiles.empty());
  const Tile& last = tiles.back();
  EXPECT_EQ(last.x, 0);
  EXPECT_EQ(last.width, 16);
  EXPECT_EQ(last.height, 16);
  // The session's image is the last complete iteration's, not a partly updated one.
  EXPECT_EQ(session.image(), last.rgba);
  EXPECT_GT(mean_channel(last.rgba, 0), 0.0);
}

TEST(Sppm, ViewportSessionsRefineSppmsOwnImage) {
  // The viewport runs SPPM's own iterations, a few per pass: after all of them its image is
  // the final render's, bit for bit (the iterations' random numbers depend on their index only).
  const auto scene = std::make_shared<Scene>(make_cornell_box());
  const RenderSettings s = sppm_settings(16, 6, 20000);
  ProgressiveSession session(scene, s, nullptr, false);
  session.start();
  EXPECT_EQ(session.target_samples(), 6);
  EXPECT_EQ(session.wait_for_samples(6, 120.0), 6);
  const ProgressiveImage image = session.image();
  const Rendered final_render = render(*scene, s);
  EXPECT_EQ(image.rgba, final_render.rgba);
}

TEST(Sppm, EmptySceneAndNoLightsRenderBlack) {
  RenderSettings s = sppm_settings(8, 2, 1000);
  const Rendered empty = render(Scene(), s);
  EXPECT_EQ(empty.stats.iterations.iterations, 2);
  EXPECT_EQ(mean_channel(empty.rgba, 0), 0.0);
  Scene dark = make_cornell_box();
  dark.lights.clear();
  const Rendered d = render(dark, s);
  EXPECT_EQ(d.stats.iterations.iterations, 2);
  EXPECT_EQ(mean_channel(d.rgba, 0), 0.0);
  EXPECT_EQ(mean_channel(d.rgba, 3), 1.0);
}

TEST(Sppm, VisiblePointsAreDiffuseOrGlossyFromRoughness03) {
  const auto bsdf_of = [](LobeType type, float alpha) {
    Bsdf bsdf(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
    Lobe lobe;
    lobe.type = type;
    lobe.alpha = alpha;
    bsdf.add(lobe);
    return bsdf;
  };
  EXPECT_TRUE(is_visible_point(bsdf_of(LobeType::kLambert, 0.0f)));
  EXPECT_TRUE(is_visible_point(bsdf_of(LobeType::kGgxReflection, 0.3f * 0.3f)));
  EXPECT_TRUE(is_visible_point(bsdf_of(LobeType::kGgxGlass, 0.25f)));
  EXPECT_FALSE(is_visible_point(bsdf_of(LobeType::kGgxReflection, 0.29f * 0.29f)));
  EXPECT_FALSE(is_visible_point(bsdf_of(LobeType::kGgxReflection, 0.0f)));  // a mirror
  EXPECT_FALSE(is_visible_point(bsdf_of(LobeType::kTransparent, 0.0f)));
  // Anisotropic: as sharp as its sharper direction.
  Bsdf aniso = bsdf_of(LobeType::kGgxReflection, 0.5f);
  Lobe lobe = aniso.lobe(0);
  lobe.alpha_y = 0.01f;
  Bsdf sharp(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
  sharp.add(lobe);
  EXPECT_FALSE(is_visible_point(sharp));
}

TEST(Sppm, PhotonsPerIterationAreScaledDownToTheMemoryBudget) {
  // 2 records per photon of kSppmPeakBytesPerRecord (81 bytes): 1e6 photons need 162 MB.
  EXPECT_EQ(kSppmPeakBytesPerRecord, 81.0);
  EXPECT_EQ(sppm_photons_that_fit(1000000, 2.0, 1e9), 1000000u);
  EXPECT_EQ(sppm_photons_that_fit(1000000, 2.0, 81e6), 500000u);
  EXPECT_EQ(sppm_photons_that_fit(1000000, 2.0, 1.0), 1u);        // never none
  EXPECT_EQ(sppm_photons_that_fit(1000000, 2.0, 0.0), 1000000u);  // unknown memory
  EXPECT_EQ(sppm_photons_that_fit(1000000, 0.0, 1.0), 1000000u);  // no photon is recorded
}

TEST(Sppm, MirrorLayerOverADiffuseVisiblePointKeepsItsReflection) {
  // A floor of 0.5 diffuse plus a 0.5 mirror under a uniform world of radiance 1: the diffuse
  // half reflects 0.5 x 1, the mirror half shows the world, 0.5 x 1. The visible point is the
  // floor; its mirror lobe must still be ray traced.
  Scene scene;
  Material floor = Material::diffuse(Vec3(0.5f));
  floor.closures.push_back(Material::mirror(Vec3(0.5f)).closures[0]);
  scene.materials.push_back(floor);
  add_mesh_instance(&scene, make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 0);
  scene.world = World::uniform(Vec3(1.0f));
  scene.camera.projection = Projection::kOrthographic;
  scene.camera.set_camera_to_world(Transform::translation(Vec3(0, 0, 3)));
  const Rendered r = render(scene, sppm_settings(8, 16, 1000));
  EXPECT_NEAR(mean_channel(r.rgba, 0), 1.0, 0.01);
}

TEST(PhotonKdTree, FindsExactlyThePhotonsWithinTheRadiusInOneOrder) {
  for (int count : {0, 5, 2000, 50000}) {
    std::vector<SppmPhoton> photons;
    for (int i = 0; i < count; ++i) {
      const float t = static_cast<float>(i);
      // Points on a few planes with repeated coordinates, as photons on walls are.
      photons.push_back(
          {Vec3(std::sin(t * 1.7f), std::round(std::cos(t * 2.3f) * 4) / 4, std::sin(t * 0.37f)),
           Vec3(0, 0, 1), Vec3(t)});
    }
    const PhotonKdTree tree(photons), again(photons);
    for (const float radius : {0.01f, 0.25f, 3.0f})
      for (const Vec3 q : {Vec3(0.1f, 0.25f, -0.3f), Vec3(0.9f, -0.9f, 0.0f)}) {
        std::vector<float> found, found_again, expected;
        tree.for_each_within(q, radius, [&](const SppmPhoton& ph) { found.push_back(ph.beta.x); });
        again.for_each_within(q, radius,
                              [&](const SppmPhoton& ph) { found_again.push_back(ph.beta.x); });
        EXPECT_EQ(found, found_again);  // the same photons in the same order: the same sum
        for (const SppmPhoton& ph : photons)
          if (dot(ph.p - q, ph.p - q) <= radius * radius) expected.push_back(ph.beta.x);
        std::sort(found.begin(), found.end());
        EXPECT_EQ(found, expected) << count << " photons, radius " << radius;
      }
  }
}

}  // namespace
}  // namespace sppm_test
}  // namespace photon

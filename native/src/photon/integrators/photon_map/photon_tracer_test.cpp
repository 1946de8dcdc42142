#include "photon/integrators/photon_map/photon_tracer.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>

#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace photon_tracer_test {
namespace {

// Everything a trace needs, built from a scene.
struct Fixture {
  explicit Fixture(Scene s)
      : scene(std::move(s)),
        resources(scene, settings, &warnings),
        context(resources.context()),
        emissive(resources.emissive()) {}
  PhotonTraceResult trace(const PhotonTraceSettings& ts, int threads = 0) {
    const PhotonSources sources(context);
    PrepareControl control;
    PhotonTraceResult r;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] { r = trace_photons(context, sources, ts, control); });
    return r;
  }
  Scene scene;
  std::vector<std::string> warnings;
  RenderSettings settings;
  SceneResources resources;
  const RenderContext& context;
  const EmissiveMeshes& emissive;
};

// A closed 2 m box (all six faces) of albedo `albedo`, so every photon hits a wall.
Scene closed_box(Vec3 albedo, Vec3 emission = Vec3(0.0f)) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(albedo).with_emission(emission));
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  return scene;
}

Light point_light(float power, Vec3 at, float radius = 0.0f) {
  Light l;
  l.type = LightType::kPoint;
  l.power = power;
  l.radius = radius;
  l.light_to_world = Transform::translation(at);
  return l;
}

TEST(PhotonTracer, DirectPhotonsCarryTheEmittedFlux) {
  for (int kind = 0; kind < 3; ++kind) {
    Scene scene = closed_box(Vec3(0.5f));
    float expected;
    if (kind == 0) {
      scene.lights.push_back(point_light(100.0f, {0.1f, 0.2f, 0.3f}));
      expected = 100.0f;
    } else if (kind == 1) {
      scene.lights.push_back(point_light(100.0f, {0.1f, 0.2f, 0.3f}, 0.2f));
      expected = 100.0f;
    } else {
      Light area;
      area.type = LightType::kArea;
      area.power = 100.0f;
      area.size_x = 0.5f;
      area.size_y = 0.25f;
      area.light_to_world = Transform::translation(Vec3(0, 0, 0.9f));
      scene.lights.push_back(area);
      expected = 100.0f * kPi / 4.0f;  // Cycles' area-light units: L = P / (4 A), Phi = pi L A
    }
    Fixture f(std::move(scene));
    PhotonTraceSettings ts;
    ts.global_photons = 50000;
    ts.caustic_photons = 0;
    const PhotonTraceResult r = f.trace(ts);
    EXPECT_EQ(r.global_emitted, 50000u);
    const Vec3 direct = total_power(r.global, kPhotonDirect);
    EXPECT_NEAR(direct.x, expected, 0.005f * expected) << "light kind " << kind;
    // Russian roulette keeps the expected flux per bounce: albedo 0.5 reflects half.
    const Vec3 once = total_power(r.global, kPhotonIndirect);
    EXPECT_NEAR(once.x, expected, 0.05f * expected) << "0.5 + 0.25 + ... = 1 x the direct flux";
  }
}

TEST(PhotonTracer, EmissiveTrianglesEmitTwoPiLATimesArea) {
  // Walls of albedo 0.5 (photons are stored only where a surface reflects diffusely).
  Scene scene = closed_box(Vec3(0.5f));
  scene.materials.push_back(Material::emission(Vec3(2.0f, 1.0f, 0.5f)));
  // A 0.4 x 0.4 emissive quad in the middle of the box, both sides emitting.
  add_mesh_instance(&scene, make_quad({-0.2f, -0.2f, 0.0f}, {0.4f, 0, 0}, {0, 0.4f, 0}), 1);
  Fixture f(std::move(scene));
  EXPECT_EQ(f.emissive.size(), 2u);
  PhotonTraceSettings ts;
  ts.global_photons = 40000;
  ts.caustic_photons = 0;
  const PhotonTraceResult r = f.trace(ts);
  const Vec3 direct = total_power(r.global, kPhotonDirect);
  const float area = 0.16f;
  EXPECT_NEAR(direct.x, 2.0f * kPi * 2.0f * area, 0.01f * 2.0f * kPi * 2.0f * area);
  EXPECT_NEAR(direct.z, 2.0f * kPi * 0.5f * area, 0.01f * 2.0f * kPi * 0.5f * area);
}

TEST(PhotonTracer, MapsDoNotDependOnThreadCount) {
  Fixture f(make_caustic_box());
  PhotonTraceSettings ts;
  ts.global_photons = 30000;
  ts.caustic_photons = 20000;
  ts.seed = 5;
  const PhotonTraceResult one = f.trace(ts, 1);
  const PhotonTraceResult two = f.trace(ts, 2);
  ASSERT_EQ(one.global.size(), two.global.size());
  ASSERT_EQ(one.caustic.size(), two.caustic.size());
  ASSERT_GT(one.caustic.size(), 0u);
  EXPECT_EQ(0,
            std::memcmp(one.global.data(), two.global.data(), one.global.size() * sizeof(Photon)));
  EXPECT_EQ(
      0, std::memcmp(one.caustic.data(), two.caustic.data(), one.caustic.size() * sizeof(Photon)));
  ts.seed = 6;
  const PhotonTraceResult other = f.trace(ts, 2);
  EXPECT_NE(0, std::memcmp(one.global.data(), other.global.data(),
                           std::min(one.global.size(), other.global.size()) * sizeof(Photon)));
}

// A glass ball (IOR 1.5, radius 0.3) resting on a black-bordered white floor, a point light
// 1.5 m above it: the caustic photons are aimed at the ball (projection), land under it, and
// carry about the flux the ball intercepts times its transmittance.
TEST(PhotonTracer, CausticPhotonsAreAimedAndFocusedUnderAGlassBall) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  scene.materials.push_back(Material::glass(1.5f));
  add_mesh_instance(&scene, make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0.3f}, 0.3f, 96, 48), 1);
  scene.lights.push_back(point_light(100.0f, {0, 0, 1.8f}));
  Fixture f(std::move(scene));
  PhotonTraceSettings ts;
  ts.global_photons = 0;
  ts.caustic_photons = 40000;
  const PhotonTraceResult r = f.trace(ts);
  EXPECT_EQ(r.caustic_emitted, 40000u);
  // Projection: most emitted caustic photons reach the ball and then the floor. Emitting
  // uniformly would waste all but (1 - cos a) / 2 = 1% of them.
  EXPECT_GT(r.caustic.size(), 30000u);
  const float d = 1.5f, radius = 0.3f;
  const float intercepted = 100.0f * 0.5f * (1.0f - std::sqrt(1.0f - radius * radius / (d * d)));
  const Vec3 flux = total_power(r.caustic, kPhotonCaustic);
  // Two Fresnel interfaces at normal-ish incidence pass ~92%; reflections off the ball are
  // caustics too (some reach the floor), so the stored flux lies between.
  EXPECT_GT(flux.x, 0.75f * intercepted);
  EXPECT_LT(flux.x, 1.0f * intercepted);
  double near = 0.0;
  for (const Photon& ph : r.caustic)
    if (length(Vec3(ph.pos().x, ph.pos().y, 0.0f)) < radius) near += ph.power().x;
  EXPECT_GT(near / flux.x, 0.7) << "the caustic is focused under the ball";
}

TEST(PhotonTracer, TimeBudgetTracesForItsTimeAndKeepsTheFlux) {
  Scene scene = closed_box(Vec3(0.5f));
  scene.lights.push_back(point_light(10.0f, {0, 0, 0}));
  Fixture f(std::move(scene));
  PhotonTraceSettings ts;
  ts.global_photons = 1000;  // only the ratio matters with a budget
  ts.caustic_photons = 0;
  ts.time_budget = 0.3;
  const PhotonTraceResult r = f.trace(ts);
  EXPECT_GE(r.seconds, 0.3);
  EXPECT_LT(r.seconds, 3.0);
  EXPECT_GT(r.global_emitted, 1000u);
  EXPECT_NEAR(total_power(r.global, kPhotonDirect).x, 10.0f, 0.05f);
}

TEST(PhotonTracer, StopEarlyKeepsTheFluxOfThePhotonsTraced) {
  Scene scene = closed_box(Vec3(0.5f));
  scene.lights.push_back(point_light(10.0f, {0, 0, 0}));
  Fixture f(std::move(scene));
  const PhotonSources sources(f.context);
  std::atomic<bool> stop{false};
  PrepareControl control;
  control.stop_early = &stop;
  int reports = 0;
  control.progress = [&](const std::string&, float) {
    if (++reports == 2) stop = true;  // "Esc" after two rounds
  };
  PhotonTraceSettings ts;
  ts.global_photons = 10000000;
  ts.caustic_photons = 0;
  const PhotonTraceResult r = trace_photons(f.context, sources, ts, control);
  EXPECT_TRUE(r.stopped_early);
  EXPECT_GT(r.global_emitted, 0u);
  EXPECT_LT(r.global_emitted, 1000000u);
  EXPECT_NEAR(total_power(r.global, kPhotonDirect).x, 10.0f, 0.05f);
}

TEST(PhotonTracer, NoLightsOrNoGeometryTraceNothing) {
  Fixture dark(closed_box(Vec3(0.5f)));
  PhotonTraceSettings ts;
  EXPECT_TRUE(dark.trace(ts).global.empty());
  Scene empty;
  empty.lights.push_back(point_light(10.0f, {0, 0, 0}));
  Fixture nothing(std::move(empty));
  EXPECT_TRUE(nothing.trace(ts).global.empty());
}

}  // namespace
}  // namespace photon_tracer_test
}  // namespace photon

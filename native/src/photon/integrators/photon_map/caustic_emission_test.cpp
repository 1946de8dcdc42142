// Caustic photons aimed at specular objects (caustic_targets.h, light_emission.cpp): for every
// light type, most emitted caustic photons must reach the target, and the flux they carry to it
// must match uniform (unaimed) emission, i.e. aiming redistributes photons without bias.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "photon/base/sampling.h"
#include "photon/integrators/photon_map/caustic_targets.h"
#include "photon/integrators/photon_map/photon_tracer.h"
#include "photon/lights/photon_aim.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace caustic_emission_test {
namespace {

struct Fixture {
  explicit Fixture(Scene s)
      : scene(std::move(s)),
        resources(scene, settings, &warnings),
        context(resources.context()),
        sources(context) {}
  Scene scene;
  std::vector<std::string> warnings;
  RenderSettings settings;
  SceneResources resources;
  const RenderContext& context;
  PhotonSources sources;
};

// A triangular glass prism (apex up) lifted above the floor: cross-section width 0.4, height 0.35
// in x/z, 0.5 long in y, its base at height `base`. Faces wound outwards.
Mesh make_prism(float base) {
  Mesh m;
  m.name = "prism";
  for (float y : {-0.25f, 0.25f}) {
    m.positions.push_back({-0.2f, y, base});
    m.positions.push_back({0.2f, y, base});
    m.positions.push_back({0.0f, y, base + 0.35f});
  }
  m.indices = {0, 1, 2, 3, 5, 4, 0, 3, 4, 0, 4, 1, 0, 2, 5, 0, 5, 3, 1, 4, 5, 1, 5, 2};
  return m;
}

// A white floor `half` metres around the origin (instance 0) and a specular object (instance 1).
Scene floor_and(Mesh target, const Material& material, float half = 5.0f) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  scene.materials.push_back(material);
  add_mesh_instance(&scene, make_quad({-half, -half, 0}, {2 * half, 0, 0}, {0, 2 * half, 0}), 0);
  add_mesh_instance(&scene, std::move(target), 1);
  return scene;
}

Light make_light(LightType type, float power, const Vec3& at) {
  Light l;
  l.type = type;
  l.power = power;
  l.light_to_world = Transform::translation(at);  // local -Z: straight down
  return l;
}

// Scenes, each with one light aimed at glass (or mirror) objects.
Scene spot_on_prism(float radius = 0.0f) {
  Scene s = floor_and(make_prism(0.3f), Material::glass(1.5f));
  Light l = make_light(LightType::kSpot, 100.0f, {0.06f, 0.0f, 2.0f});
  l.spot_size = 2.0f * kPi / 180.0f;
  l.radius = radius;
  s.lights.push_back(l);
  return s;
}
Scene point_on_ball() {
  Scene s = floor_and(make_uv_sphere({0, 0, 0.25f}, 0.25f, 64, 32), Material::glass(1.5f));
  s.lights.push_back(make_light(LightType::kPoint, 100.0f, {0.0f, 0.0f, 0.9f}));
  return s;
}
Scene sphere_light_on_ball() {
  Scene s = point_on_ball();
  s.lights[0].radius = 0.1f;
  return s;
}
// A 0.5 m square light facing down at z = 1 with a glass ball whose centre lies 5 cm behind the
// light's plane (half of it faces the light) and a mirror ball wholly behind it.
Scene area_light_beside_balls() {
  Scene s = floor_and(make_uv_sphere({0.45f, 0, 1.05f}, 0.2f, 64, 32), Material::glass(1.5f));
  s.materials.push_back(Material::mirror(Vec3(0.9f)));
  add_mesh_instance(&s, make_uv_sphere({-0.5f, 0, 1.5f}, 0.2f, 64, 32), 2);
  Light l = make_light(LightType::kArea, 100.0f, {0.0f, 0.0f, 1.0f});
  l.size_x = l.size_y = 0.5f;
  s.lights.push_back(l);
  return s;
}
// A sun 2 degrees wide, 30 degrees from the zenith, over a glass ball on a floor `half` metres
// wide each way (the scene's size sets the disc unaimed sun photons are spread over).
Scene sun_on_ball(float half) {
  Scene s = floor_and(make_uv_sphere({0, 0, 0.3f}, 0.3f, 64, 32), Material::glass(1.5f), half);
  Light l = make_light(LightType::kSun, 3.0f, {0, 0, 0});
  const float a = 30.0f * kPi / 180.0f;
  // Rotation about x: local -Z (the direction the light travels) becomes (0, sin a, -cos a).
  const float rows[12] = {1, 0, 0,           0,           0, std::cos(a), -std::sin(a),
                          0, 0, std::sin(a), std::cos(a), 0};
  l.light_to_world = Transform::from_rows(rows);
  l.sun_angle = 2.0f * kPi / 180.0f;
  s.lights.push_back(l);
  return s;
}

// The flux that emitted photons carry to their first hit on the instances in [first, last], as
// a mean over `n` photons (the estimate of the flux) and its standard error.
struct FluxEstimate {
  double mean = 0.0, sigma = 0.0;
  double hit_fraction = 0.0;  // of emitted photons
};

FluxEstimate flux_to(const Fixture& f, bool caustic, uint64_t n, uint32_t first, uint32_t last,
                     uint64_t seed = 1) {
  double sum = 0.0, sum2 = 0.0;
  uint64_t hits = 0;
  for (uint64_t i = 0; i < n; ++i) {
    // Unstratified samples, so the standard error below is the one of independent photons.
    Sampler sampler(seed, 0xF1u, static_cast<uint32_t>(i));
    EmittedPhoton e;
    const bool ok =
        caustic ? f.sources.emit_caustic(sampler, &e) : f.sources.emit_global(sampler, &e);
    if (!ok) continue;
    Hit hit;
    if (!f.context.accel->intersect(e.ray, kVisibleAll, &hit)) continue;
    const uint32_t inst = f.context.accel->scene_instance(hit.instance);
    if (inst < first || inst > last) continue;
    const double x = e.power.x;
    sum += x;
    sum2 += x * x;
    ++hits;
  }
  FluxEstimate r;
  r.mean = sum / n;
  r.sigma = std::sqrt(std::max(0.0, sum2 / n - r.mean * r.mean) / n);
  r.hit_fraction = static_cast<double>(hits) / n;
  return r;
}

PhotonTraceResult trace_caustics(const Fixture& f, uint64_t n, int threads = 0, uint64_t seed = 0) {
  PhotonTraceSettings ts;
  ts.global_photons = 0;
  ts.caustic_photons = n;
  ts.seed = seed;
  PrepareControl control;
  PhotonTraceResult r;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] { r = trace_photons(f.context, f.sources, ts, control); });
  return r;
}

// Aimed (caustic) against unaimed (global) emission: the fraction of caustic photons that reach
// the targets is at least `min_fraction`, and the flux they bring agrees within 4 standard errors
// of the difference (both estimates are means of independent photons), each known to 2%.
void expect_aimed_and_unbiased(const char* name, const Fixture& f, uint32_t first, uint32_t last,
                               double min_fraction, uint64_t n_reference) {
  const FluxEstimate aimed = flux_to(f, true, 200000, first, last, 1);
  const FluxEstimate uniform = flux_to(f, false, n_reference, first, last, 2);
  const PhotonTraceResult traced = trace_caustics(f, 100000);
  std::printf(
      "%-22s aimed: %.4f reach the target, flux %.5g +- %.2g; stored %zu per 100k | "
      "uniform: %.5f reach, flux %.5g +- %.2g\n",
      name, aimed.hit_fraction, aimed.mean, aimed.sigma, traced.caustic.size(),
      uniform.hit_fraction, uniform.mean, uniform.sigma);
  EXPECT_GT(aimed.hit_fraction, min_fraction) << name;
  ASSERT_GT(uniform.mean, 0.0) << name;
  EXPECT_LT(aimed.sigma, 0.02 * uniform.mean) << name;
  EXPECT_LT(uniform.sigma, 0.02 * uniform.mean) << name << ": reference too noisy";
  const double sigma = std::hypot(aimed.sigma, uniform.sigma);
  EXPECT_NEAR(aimed.mean, uniform.mean, 4.0 * sigma) << name;
}

TEST(CausticEmission, NarrowSpotReachesThePrismAndKeepsItsFlux) {
  Fixture f(spot_on_prism());
  expect_aimed_and_unbiased("spot 2 deg", f, 1, 1, 0.5, 200000);
}

TEST(CausticEmission, NarrowSpotWithARadiusReachesThePrismAndKeepsItsFlux) {
  Fixture f(spot_on_prism(0.02f));
  expect_aimed_and_unbiased("spot 2 deg, r 2 cm", f, 1, 1, 0.5, 200000);
}

TEST(CausticEmission, PointLightReachesTheBallAndKeepsItsFlux) {
  Fixture f(point_on_ball());
  expect_aimed_and_unbiased("point", f, 1, 1, 0.9, 400000);
}

TEST(CausticEmission, SphereLightEmitsOnlyFromTheSideThatSeesTheBall) {
  Fixture f(sphere_light_on_ball());
  expect_aimed_and_unbiased("sphere light r 0.1", f, 1, 1, 0.8, 400000);
}

TEST(CausticEmission, AreaLightSkipsTargetsBehindItsPlane) {
  Fixture f(area_light_beside_balls());
  // The mirror ball above the light receives nothing; the half-hidden glass ball everything.
  expect_aimed_and_unbiased("area, ball half behind", f, 1, 2, 0.8, 400000);
  EXPECT_EQ(flux_to(f, true, 20000, 2, 2).hit_fraction, 0.0);
}

TEST(CausticEmission, SunReachesTheBallInALargeScene) {
  // 100 m of floor: unaimed sun photons cover the whole scene, aimed ones only the ball.
  Fixture big(sun_on_ball(50.0f));
  const FluxEstimate aimed = flux_to(big, true, 100000, 1, 1);
  const PhotonTraceResult traced = trace_caustics(big, 100000);
  std::printf("%-22s aimed: %.4f reach the target, flux %.5g +- %.2g; stored %zu per 100k\n",
              "sun 2 deg, 100 m floor", aimed.hit_fraction, aimed.mean, aimed.sigma,
              traced.caustic.size());
  EXPECT_GT(aimed.hit_fraction, 0.8);
  // The ball intercepts the beam over (nearly) its cross-section: E pi r^2 (the mesh's polygons
  // make it a little smaller).
  const double expected = 3.0 * 3.14159265358979 * 0.3 * 0.3;
  EXPECT_LT(aimed.mean, expected * 1.0);
  EXPECT_GT(aimed.mean, expected * 0.97);
}

TEST(CausticEmission, SunKeepsItsFluxAgainstUniformEmission) {
  // A small scene, so uniform emission over the scene's disc hits the ball often enough.
  Fixture f(sun_on_ball(0.8f));
  expect_aimed_and_unbiased("sun 2 deg, 1.6 m floor", f, 1, 1, 0.8, 400000);
}

// All light types at once: aimed caustic maps are the same whatever the number of threads.
TEST(CausticEmission, MapsDoNotDependOnThreadCount) {
  Scene s = area_light_beside_balls();
  add_mesh_instance(&s, make_prism(0.3f), 1);
  Scene spot = spot_on_prism(0.01f), sphere = sphere_light_on_ball(), sun = sun_on_ball(5.0f);
  for (const Scene* other : {&spot, &sphere, &sun}) s.lights.push_back(other->lights[0]);
  Fixture f(std::move(s));
  const PhotonTraceResult one = trace_caustics(f, 30000, 1, 3);
  const PhotonTraceResult two = trace_caustics(f, 30000, 2, 3);
  ASSERT_GT(one.caustic.size(), 1000u);
  ASSERT_EQ(one.caustic.size(), two.caustic.size());
  EXPECT_EQ(
      0, std::memcmp(one.caustic.data(), two.caustic.data(), one.caustic.size() * sizeof(Photon)));
}

}  // namespace
}  // namespace caustic_emission_test
}  // namespace photon

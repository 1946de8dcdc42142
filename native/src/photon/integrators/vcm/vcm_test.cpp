#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace vcm_test {
namespace {

RenderSettings vcm_settings(int size, int iterations, uint64_t paths, VcmMode mode) {
  RenderSettings s;
  s.full_width = s.full_height = size;
  s.x1 = s.y1 = size;
  s.seed = 7;
  s.integrator = IntegratorType::kVcm;
  s.vcm_mode = mode;
  s.vcm_iterations = iterations;
  s.vcm_light_paths = paths;
  return s;
}

struct Rendered {
  std::vector<float> rgba;
  RenderStats stats;
};

Rendered render(const Scene& scene, const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(scene), s);
  session.start();
  session.wait();
  return {session.image(), session.stats()};
}

// The mean of channel c, each pixel's value taken at most `ceiling`.
double mean_channel(const std::vector<float>& rgba, int c, float ceiling = INFINITY) {
  double sum = 0.0;
  for (size_t i = c; i < rgba.size(); i += 4) sum += std::min(rgba[i], ceiling);
  return sum / (rgba.size() / 4);
}

const char* name(VcmMode m) {
  return m == VcmMode::kVcm ? "VCM" : m == VcmMode::kBpt ? "BPT" : "PPM";
}

// A closed box whose walls emit Le and reflect albedo rho: L = Le / (1 - rho) everywhere.
Scene emissive_furnace(float rho, float le) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(rho)).with_emission(Vec3(le)));
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  scene.camera = make_look_at_camera({0, -0.5f, 0}, {0, 1, 0.2f}, 1.2f, 1.0f);
  return scene;
}

TEST(Vcm, EmissiveFurnaceConvergesToLeOverOneMinusAlbedoInEveryMode) {
  for (VcmMode mode : {VcmMode::kVcm, VcmMode::kBpt, VcmMode::kPpm}) {
    const Rendered r = render(emissive_furnace(0.6f, 1.0f), vcm_settings(24, 8, 2000, mode));
    EXPECT_EQ(r.stats.iterations.iterations, 8) << name(mode);
    EXPECT_NEAR(mean_channel(r.rgba, 0), 1.0 / (1.0 - 0.6), 0.02 * 2.5) << name(mode);
    EXPECT_NEAR(mean_channel(r.rgba, 3), 1.0, 1e-6) << name(mode);
  }
}

// A diffuse plane under a point light of intensity I at height h, seen from above by a pinhole:
// L = rho / pi I cos(theta) / d^2 and no indirect light.
TEST(Vcm, PlaneUnderPointLightMatchesInverseSquareLawInEveryMode) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
  add_mesh_instance(&scene, make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 0);
  Light light;
  light.type = LightType::kPoint;
  light.power = 100.0f;
  const float h = 1.0f;
  light.light_to_world = Transform::translation(Vec3(0, 0, h));
  scene.lights.push_back(light);
  // Looking straight down from z = 3 with a window of +-0.11 at distance 1: +-0.33 on the plane.
  scene.camera.set_camera_to_world(Transform::translation(Vec3(0, 0, 3)));
  scene.camera.window_min_x = scene.camera.window_min_y = -0.11f;
  scene.camera.window_max_x = scene.camera.window_max_y = 0.11f;
  const double intensity = 100.0 / (4.0 * kPi);
  for (VcmMode mode : {VcmMode::kVcm, VcmMode::kBpt, VcmMode::kPpm}) {
    const Rendered r = render(scene, vcm_settings(33, 16, 20000, mode));
    // Mean of a 5 x 5 block around a pixel (the merging radius blurs a little in PPM/VCM).
    auto block = [&](int x, int y) {
      double sum = 0.0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          sum += r.rgba[(static_cast<size_t>(y + dy) * 33 + x + dx) * 4];
      return sum / 25.0;
    };
    const double centre = 0.5 / kPi * intensity / (h * h);
    EXPECT_NEAR(block(16, 16), centre, 0.03 * centre) << name(mode);
    // 13 pixels off centre: 13 / 16.5 * 0.33 = 0.26 on the plane.
    const double rr = 13.0 / 16.5 * 0.33, d2 = h * h + rr * rr;
    const double expected = 0.5 / kPi * intensity * (h / std::sqrt(d2)) / d2;
    for (auto [x, y] : {std::pair{3, 16}, std::pair{29, 16}, std::pair{16, 3}, std::pair{16, 29}})
      EXPECT_NEAR(block(x, y), expected, 0.04 * expected) << name(mode) << " " << x << "," << y;
  }
}

TEST(Vcm, CornellBoxMeanAgreesWithSppmAndPhotonMapping) {
  const Scene scene = make_cornell_box();
  RenderSettings reference = vcm_settings(32, 32, 20000, VcmMode::kVcm);
  reference.integrator = IntegratorType::kSppm;
  const Rendered sppm = render(scene, reference);
  RenderSettings pm = reference;
  pm.integrator = IntegratorType::kPhotonMap;
  pm.samples = 16;
  const Rendered photon_map = render(scene, pm);
  for (int c = 0; c < 3; ++c) {
    const double ref = mean_channel(sppm.rgba, c);
    EXPECT_NEAR(mean_channel(photon_map.rgba, c), ref, 0.05 * ref) << "PHOTON_MAP channel " << c;
    for (VcmMode mode : {VcmMode::kVcm, VcmMode::kBpt, VcmMode::kPpm}) {
      const Rendered r = render(scene, vcm_settings(32, 16, 20000, mode));
      EXPECT_NEAR(mean_channel(r.rgba, c), ref, 0.04 * ref) << name(mode) << " channel " << c;
    }
  }
}

// Glass and mirror (delta lobes: no connections or merging there, pdfs as discrete
// probabilities) and the caustic they cast.
TEST(Vcm, CausticBoxMeanAgreesWithSppm) {
  const Scene scene = make_caustic_box();
  RenderSettings reference = vcm_settings(32, 64, 20000, VcmMode::kVcm);
  reference.integrator = IntegratorType::kSppm;
  const Rendered sppm = render(scene, reference);
  // The lamp's highlights in the balls (a sphere of radius 0.05, hundreds of times brighter
  // than the walls) cover a fraction of a pixel here, so where a few samples land decides the
  // plain mean; pixels are compared up to 20, above every pixel of the caustic.
  constexpr float kCeiling = 20.0f;
  for (VcmMode mode : {VcmMode::kVcm, VcmMode::kBpt, VcmMode::kPpm}) {
    const Rendered r = render(scene, vcm_settings(32, 16, 20000, mode));
    for (int c = 0; c < 3; ++c) {
      const double ref = mean_channel(sppm.rgba, c, kCeiling);
      const double mean = mean_channel(r.rgba, c, kCeiling);
      std::printf("caustic box %s channel %d: %.4f, SPPM %.4f\n", name(mode), c, mean, ref);
      EXPECT_NEAR(mean, ref, 0.04 * ref) << name(mode) << " channel " << c;
    }
  }
}

// A translucent sheet lit only from behind: every light vertex merged at the sheet's lit side
// arrives through it, from the other side of the surface the camera sees. Merging must count
// it as SPPM's gathering does (the BSDF says what crosses), or PPM mode renders the sheet black
// and VCM loses merging's share of the weights.
TEST(Vcm, LightMergedThroughATranslucentSheetAgreesWithConnectionsAndSppm) {
  Scene scene;
  Closure translucent;
  translucent.type = ClosureType::kTranslucent;
  translucent[Param::kColor] = Input::constant(Vec3(0.8f));
  Material sheet;
  sheet.name = "sheet";
  sheet.closures = {translucent};
  scene.materials.push_back(sheet);
  add_mesh_instance(&scene, make_quad({-1, -1, 1}, {2, 0, 0}, {0, 2, 0}), 0);
  // An emissive square under the sheet, facing up; the camera looks down at the sheet.
  scene.materials.push_back(Material::emission(Vec3(4.0f)));
  add_mesh_instance(&scene, make_quad({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0}), 1);
  scene.camera = make_look_at_camera({0, -0.3f, 3}, {0, 0, 1}, 0.6f, 1.0f);
  RenderSettings reference = vcm_settings(24, 8, 20000, VcmMode::kBpt);
  const double bpt = mean_channel(render(scene, reference).rgba, 0);
  ASSERT_GT(bpt, 0.05);
  reference.integrator = IntegratorType::kSppm;
  EXPECT_NEAR(mean_channel(render(scene, reference).rgba, 0), bpt, 0.03 * bpt) << "SPPM";
  for (VcmMode mode : {VcmMode::kVcm, VcmMode::kPpm}) {
    const Rendered r = render(scene, vcm_settings(24, 8, 20000, mode));
    EXPECT_NEAR(mean_channel(r.rgba, 0), bpt, 0.03 * bpt) << name(mode);
  }
}

// A camera VCM cannot connect to renders with SPPM, and says so.
TEST(Vcm, OrthographicCameraFallsBackToSppmWithAWarning) {
  Scene scene = make_cornell_box();
  scene.camera.projection = Projection::kOrthographic;
  RenderSession session(std::make_shared<Scene>(scene), vcm_settings(16, 2, 1000, VcmMode::kVcm));
  session.start();
  session.wait();
  bool warned = false;
  for (const std::string& w : session.warnings())
    warned = warned || w.find("rendering with SPPM instead") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_EQ(session.stats().iterations.iterations, 2);
}

// A point lamp with a radius is a sphere camera paths can meet: seen in a mirror it shows its
// radiance I / (pi r^2) as ray tracing shows it, in every mode (as a point it was black).
TEST(Vcm, SphereLampSeenInAMirrorMatchesRayTracing) {
  Scene scene;
  scene.materials.push_back(Material::mirror(Vec3(1.0f)));
  add_mesh_instance(&scene, make_quad({-5, -5, 0}, {10, 0, 0}, {0, 10, 0}), 0);
  Light lamp;
  lamp.name = "sphere";
  lamp.type = LightType::kPoint;
  lamp.power = 100.0f;
  lamp.radius = 0.4f;
  lamp.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 1.0f));
  scene.lights.push_back(lamp);
  // Looking 45 degrees down at the lamp's mirror image; the lamp itself is out of view.
  scene.camera = make_look_at_camera({0, -2, 1}, {0, 0, -1}, 0.5f, 1.0f);
  RenderSettings traced = vcm_settings(32, 1, 1000, VcmMode::kVcm);
  traced.integrator = IntegratorType::kRayTrace;
  traced.samples = 16;
  const double expected = mean_channel(render(scene, traced).rgba, 0);
  // The reflection covers about a tenth of the frame at L = 100 / (4 pi) / (pi 0.16).
  ASSERT_GT(expected, 0.5);
  for (VcmMode mode : {VcmMode::kVcm, VcmMode::kBpt, VcmMode::kPpm}) {
    const double mean = mean_channel(render(scene, vcm_settings(32, 16, 1000, mode)).rgba, 0);
    EXPECT_NEAR(mean, expected, 0.03 * expected) << name(mode);
  }
}

TEST(Vcm, ImageIsTheSameForAnyThreadCount) {
  const Scene scene = make_caustic_box();
  RenderSettings s = vcm_settings(32, 3, 5000, VcmMode::kVcm);
  std::vector<float> reference;
  for (int threads : {1, 2, 3}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    s.threads = threads;
    const Rendered r = render(scene, s);
    EXPECT_GT(mean_channel(r.rgba, 0), 0.01);
    if (reference.empty())
      reference = r.rgba;
    else
      EXPECT_EQ(r.rgba, reference) << threads << " threads";
  }
}

}  // namespace
}  // namespace vcm_test
}  // namespace photon

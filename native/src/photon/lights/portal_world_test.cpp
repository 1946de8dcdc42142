// The world seen through portals (portal_world.h): light samples and their density, direct
// lighting in a room lit through a window (the same mean as without the portal, far less
// noise), and photons that carry the world's flux and the window's share of it.
#include "photon/lights/portal_world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "photon/base/rng.h"
#include "photon/base/sampling.h"
#include "photon/lights/direct_lighting.h"
#include "photon/lights/environment.h"
#include "photon/lights/world_light.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace portal_world_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

double mean3(const Vec3& v) {
  return (static_cast<double>(v.x) + v.y + v.z) / 3.0;
}

// L(w) = a + b w.z + c w.x, a sky brighter above and towards +x.
Vec3 sky(const Vec3& w) {
  return Vec3(1.0f, 0.8f, 0.6f) + Vec3(0.5f, 0.3f, 0.2f) * w.z + Vec3(0.4f, 0.2f, 0.1f) * w.x;
}

// The window of the room below: 0.8 wide, 0.6 tall, in the wall x = 1, light going along -x.
Portal window_portal() {
  Portal p;
  p.name = "window";
  p.center = Vec3(1.0f, 0.0f, 1.0f);
  p.half_x = Vec3(0.0f, 0.4f, 0.0f);
  p.half_y = Vec3(0.0f, 0.0f, 0.3f);
  p.direction = Vec3(-1.0f, 0.0f, 0.0f);
  return p;
}

// A closed room [-1, 1]^2 x [0, 2] with that window cut into the wall x = 1, under a world.
std::shared_ptr<Scene> room(bool with_portal, bool environment) {
  auto scene = std::make_shared<Scene>();
  scene->materials.push_back(Material::diffuse(Vec3(0.5f), "walls"));
  auto quad = [&](const Vec3& corner, const Vec3& u, const Vec3& v) {
    add_mesh_instance(scene.get(), make_quad(corner, u, v), 0);
  };
  quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0});    // floor
  quad({-1, -1, 2}, {0, 2, 0}, {2, 0, 0});    // ceiling
  quad({-1, -1, 0}, {0, 0, 2}, {0, 2, 0});    // x = -1
  quad({-1, -1, 0}, {2, 0, 0}, {0, 0, 2});    // y = -1
  quad({-1, 1, 0}, {0, 0, 2}, {2, 0, 0});     // y = 1
  quad({1, -1, 0}, {0, 2, 0}, {0, 0, 0.7f});  // x = 1 below the window
  quad({1, -1, 1.3f}, {0, 2, 0}, {0, 0, 0.7f});
  quad({1, -1, 0.7f}, {0, 0.6f, 0}, {0, 0, 0.6f});
  quad({1, 0.4f, 0.7f}, {0, 0.6f, 0}, {0, 0, 0.6f});
  if (environment) {
    scene->world.radiance = sky;
    scene->world.sample_map_width = 128;
  } else {
    scene->world.color = Vec3(1.0f, 0.9f, 0.8f);
  }
  if (with_portal) scene->portals.push_back(window_portal());
  return scene;
}

SurfaceInteraction floor_point(const Scene& scene, const Vec3& p) {
  SurfaceInteraction si;
  si.p = p;
  si.ng = si.ns = Vec3(0.0f, 0.0f, 1.0f);
  si.mat = &scene.materials[0];
  si.material = 0;
  return si;
}

struct Estimate {
  Vec3 mean;
  double standard_error;
};

Estimate direct_irradiance_in(const Scene& scene, const Vec3& p, int n) {
  RenderSettings settings;
  const SceneResources resources(scene, settings, nullptr);
  const SurfaceInteraction si = floor_point(scene, p);
  Vec3 sum(0.0f);
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(7, 1, static_cast<uint32_t>(i), n);
    const Vec3 e = direct_irradiance(resources.context(), si, sampler);
    sum += e;
    sum2 += mean3(e) * mean3(e);
  }
  const Vec3 mean = sum / static_cast<float>(n);
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean3(mean) * mean3(mean)) / n)};
}

TEST(PortalWorld, WindowLitFloorKeepsItsMeanWithFarLessNoise) {
  for (bool environment : {false, true}) {
    const auto plain = room(false, environment), guided = room(true, environment);
    const Vec3 p(-0.2f, 0.1f, 0.0f);
    const int n = 40000;
    const Estimate without = direct_irradiance_in(*plain, p, n);
    const Estimate with = direct_irradiance_in(*guided, p, n);
    ASSERT_GT(mean3(without.mean), 0.0);
    const double se = std::hypot(without.standard_error, with.standard_error);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(with.mean[k], without.mean[k], 5.0 * se) << "channel " << k;
    std::printf("%s: floor irradiance %.4f +- %.4f through the portal, %.4f +- %.4f without\n",
                environment ? "sky" : "uniform world", mean3(with.mean), with.standard_error,
                mean3(without.mean), without.standard_error);
    // Measured: 6x (the uniform world, which without the portal only BSDF samples reach) and
    // 5x (the sky's table) lower.
    EXPECT_LT(with.standard_error * 3.0, without.standard_error)
        << (environment ? "environment" : "uniform world") << ": " << with.standard_error
        << " against " << without.standard_error;
  }
}

TEST(PortalWorld, LightSamplesReportTheDensityBsdfSamplesAreWeightedWith) {
  const WorldEmitter uniform(Vec3(1.0f));
  const EnvironmentEmitter environment(sky, 64);
  for (const Emitter* world :
       {static_cast<const Emitter*>(&uniform), static_cast<const Emitter*>(&environment)}) {
    const PortalWorldEmitter guided(*world, PortalSet({window_portal()}));
    EXPECT_FALSE(guided.flags() & kEmitterBsdfSampledOnly);
    for (const Vec3& p : {Vec3(0.0f, 0.0f, 0.5f), Vec3(3.0f, 0.0f, 0.5f)}) {
      // The irradiance of a plane facing +z from the whole upper hemisphere (the emitter
      // alone: nothing occludes), by light samples.
      const int n = 200000;
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        Sampler sampler(5, 0, static_cast<uint32_t>(i), n);
        LightSample ls;
        if (!guided.sample_li(p, guided.draw_li(sampler), nullptr, &ls)) continue;
        ASSERT_NEAR(ls.pdf, guided.pdf_li_at_infinity(p, ls.wi), 1e-5f * ls.pdf);
        sum += mean3(ls.weight) * std::max(ls.wi.z, 0.0f);
      }
      // pi a + 2 pi b / 3 for the sky, pi for the uniform white world.
      const double exact =
          world == &uniform ? kPiD : kPiD * 0.8 + 2.0 * kPiD / 3.0 * (0.5 + 0.3 + 0.2) / 3.0;
      EXPECT_NEAR(sum / n, exact, 0.01 * exact) << "p.x = " << p.x;
    }
  }
}

TEST(PortalWorld, PhotonsCarryTheWorldsFluxAndTheWindowsShare) {
  // A uniform world L: through the disc of radius R it sends 4 pi^2 R^2 L, through the window
  // (area A, inward) pi A L.
  const WorldEmitter world(Vec3(1.0f));
  const Portal portal = window_portal();
  const PortalWorldEmitter guided(world, PortalSet({portal}));
  const PhotonFrame frame{Vec3(0.0f, 0.0f, 1.0f), 2.5f};
  const int n = 1000000;
  double total = 0.0, through_window = 0.0;
  int via_window = 0;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(6, 0, static_cast<uint32_t>(i), n);
    const float u_rest = sampler.get_1d();
    const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
    EmittedPhoton photon;
    if (!guided.sample_le(frame, u_rest, u_pos, u_dir, false, &photon)) continue;
    ASSERT_TRUE(is_finite(photon.power));
    const Ray& r = photon.ray;
    // Every photon starts outside the scene's sphere.
    ASSERT_GE(length(r.origin - frame.center), frame.radius * 0.999f);
    total += mean3(photon.power);
    if (r.direction.x < 0.0f) {
      const float t = (1.0f - r.origin.x) / r.direction.x;
      const Vec3 q = r.origin + r.direction * t;
      if (std::fabs(q.y) <= 0.4f && std::fabs(q.z - 1.0f) <= 0.3f) {
        through_window += mean3(photon.power);
        ++via_window;
      }
    }
  }
  const double area = 0.8 * 0.6;
  EXPECT_NEAR(total / n, 4.0 * kPiD * kPiD * 2.5 * 2.5, 0.01 * 4.0 * kPiD * kPiD * 6.25);
  EXPECT_NEAR(through_window / n, kPiD * area, 0.01 * kPiD * area);
  // About half the photons come through the window (without the portal: 1 in 150).
  EXPECT_GT(via_window, n / 3);
}

TEST(PortalWorld, BidirectionalRequestsSeeTheWorldAlone) {
  const EnvironmentEmitter environment(sky, 64);
  const PortalWorldEmitter guided(environment, PortalSet({window_portal()}));
  const PhotonFrame frame{Vec3(0.0f), 3.0f};
  LightSampleU u;
  u.pick = 0.1f;
  u.uv = Vec2(0.3f, 0.7f);
  LightSample a, b;
  ASSERT_TRUE(guided.sample_li(Vec3(0.0f), u, &frame, &a));
  ASSERT_TRUE(environment.sample_li(Vec3(0.0f), u, &frame, &b));
  EXPECT_EQ(a.wi.x, b.wi.x);
  EXPECT_EQ(a.direct_pdf, b.direct_pdf);
  EXPECT_EQ(guided.pdf_at_infinity(a.wi, true), environment.pdf_at_infinity(a.wi, true));
}

}  // namespace
}  // namespace portal_world_test
}  // namespace photon

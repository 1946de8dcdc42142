// The importance-sampled environment (environment.h): its density, its samples, direct lighting
// with it (analytic irradiance, the sun's noise against BSDF sampling alone), the background
// and reflections, furnaces, and photon emission against the radiance's integral.
#include "photon/lights/environment.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "photon/base/rng.h"
#include "photon/base/sampling.h"
#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/lights/direct_lighting.h"
#include "photon/lights/world_light.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace environment_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

double mean3(const Vec3& v) {
  return (static_cast<double>(v.x) + v.y + v.z) / 3.0;
}

// L(w) = a + b w.z + c w.x: positive everywhere when a > |(b, c)|. A plane facing +z receives
// E = pi a + 2 pi b / 3 from the upper hemisphere (the x term cancels), one facing -z
// pi a - 2 pi b / 3.
struct LinearSky {
  Vec3 a{1.0f, 0.8f, 0.6f}, b{0.5f, 0.3f, 0.2f}, c{0.4f, 0.2f, 0.1f};
  Vec3 operator()(const Vec3& w) const { return a + b * w.z + c * w.x; }
  Vec3 irradiance(float side) const { return a * kPi + b * (side * 2.0f * kPi / 3.0f); }
};

// A dim linear sky plus a sun: radiance 1e4 added inside a disc 0.5 degrees across (1.4
// texels of a 1024-wide map) at 40 degrees elevation. The sun's disc lies above the horizon, so
// it adds pi L sin^2(alpha) cos(theta) to a +z plane's irradiance (a uniform spherical cap).
struct SunSky {
  LinearSky sky{Vec3(0.2f), Vec3(0.1f), Vec3(0.05f)};
  float sun_radiance = 1e4f;
  double half_angle = 0.25 * kPiD / 180.0;
  double elevation = 40.0 * kPiD / 180.0, azimuth = 30.0 * kPiD / 180.0;
  Vec3 sun() const {
    return Vec3(static_cast<float>(std::cos(elevation) * std::cos(azimuth)),
                static_cast<float>(std::cos(elevation) * std::sin(azimuth)),
                static_cast<float>(std::sin(elevation)));
  }
  Vec3 operator()(const Vec3& w) const {
    const bool in_sun = dot(w, sun()) > static_cast<float>(std::cos(half_angle));
    return sky(w) + Vec3(in_sun ? sun_radiance : 0.0f);
  }
  double irradiance_up() const {
    const double s = std::sin(half_angle);
    return mean3(sky.irradiance(1.0f)) + kPiD * sun_radiance * s * s * std::sin(elevation);
  }
};

// A smooth lobe over a sky gradient and a dark ground: a varied but well-resolved density.
Vec3 lobe_sky(const Vec3& w) {
  const Vec3 axis = normalize(Vec3(0.3f, -0.5f, 0.6f));
  const float lobe = 8.0f * std::exp(-12.0f * (1.0f - dot(w, axis)));
  return Vec3(0.05f + lobe, 0.1f + 0.5f * lobe, w.z > 0.0f ? 0.3f + 0.2f * w.z : 0.02f);
}

// Solid angle of the band z1 < z < z0 over an azimuth range dphi.
double band_solid_angle(double z0, double z1, double dphi) {
  return (z0 - z1) * dphi;
}

// Sum of pdf x solid angle over an n-per-texel-axis grid of cells, each inside one texel (the
// density is constant on texels, so this is its exact integral up to rounding).
double integrate_pdf(const EnvironmentEmitter& env, int n) {
  const int rows = env.height() * n, cols = env.width() * n;
  double sum = 0.0;
  for (int i = 0; i < rows; ++i) {
    const double t0 = kPiD * i / rows, t1 = kPiD * (i + 1) / rows;
    const double z0 = std::cos(t0), z1 = std::cos(t1), zm = std::cos(0.5 * (t0 + t1));
    const double omega = band_solid_angle(z0, z1, 2.0 * kPiD / cols);
    const double s = std::sqrt(std::max(0.0, 1.0 - zm * zm));
    for (int j = 0; j < cols; ++j) {
      const double phi = 2.0 * kPiD * (j + 0.5) / cols;
      const Vec3 d(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                   static_cast<float>(zm));
      sum += env.pdf_at_infinity(d) * omega;
    }
  }
  return sum;
}

TEST(Environment, PdfIntegratesToOneOverTheSphere) {
  const EnvironmentEmitter sun(SunSky{}, 1024);
  EXPECT_NEAR(integrate_pdf(sun, 2), 1.0, 1e-4);
  const EnvironmentEmitter lobe(lobe_sky, 64);
  EXPECT_NEAR(integrate_pdf(lobe, 3), 1.0, 1e-5);
  // A black function: the table is empty and the density uniform.
  const EnvironmentEmitter black([](const Vec3&) { return Vec3(0.0f); }, 64);
  EXPECT_NEAR(integrate_pdf(black, 1), 1.0, 1e-5);
  EXPECT_FLOAT_EQ(black.pdf_at_infinity(Vec3(0, 0, 1)), 1.0f / (4.0f * kPi));
}

// The direction at the centre of texel (i, j) (mid phi, mid cos theta).
Vec3 texel_centre(int i, int j, int width, int height) {
  const double z = 0.5 * (std::cos(kPiD * i / height) + std::cos(kPiD * (i + 1) / height));
  const double s = std::sqrt(1.0 - z * z), phi = 2.0 * kPiD * (j + 0.5) / width;
  return Vec3(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
              static_cast<float>(z));
}

TEST(Environment, PdfIsTheDilatedFunctionOverItsIntegralPlusTheUniformShare) {
  // A texel's weight is the largest of the function at its centre and its eight neighbours'
  // centres (columns wrap around, rows stop at the poles), each texel of its solid angle.
  const int width = 64, height = 32;
  const EnvironmentEmitter env(lobe_sky, width);
  const float share = EnvironmentEmitter::kUniformShare;
  std::vector<double> centre(width * height), weight(width * height);
  for (int i = 0; i < height; ++i)
    for (int j = 0; j < width; ++j)
      centre[i * width + j] = mean3(lobe_sky(texel_centre(i, j, width, height)));
  double total = 0.0;
  for (int i = 0; i < height; ++i) {
    const double solid_angle =
        2.0 * kPiD / width * (std::cos(kPiD * i / height) - std::cos(kPiD * (i + 1) / height));
    for (int j = 0; j < width; ++j) {
      double w = 0.0;
      for (int di = std::max(i - 1, 0); di <= std::min(i + 1, height - 1); ++di)
        for (int dj = j - 1; dj <= j + 1; ++dj)
          w = std::max(w, centre[di * width + (dj + width) % width]);
      weight[i * width + j] = w;
      total += w * solid_angle;
    }
  }
  for (int i = 0; i < height; ++i)
    for (int j = 0; j < width; ++j) {
      const double expected = (1.0 - share) * weight[i * width + j] / total + share / (4.0 * kPiD);
      ASSERT_NEAR(env.pdf_at_infinity(texel_centre(i, j, width, height)), expected, 1e-4 * expected)
          << "texel " << i << ", " << j;
    }
}

// A bright pixel of a filtered texture spreads into its neighbours: they are sampled as densely
// as it is, so no direction's radiance stands far above its density.
TEST(Environment, TexelsBesideABrightSpotAreSampledLikeIt) {
  const int width = 64, height = 32;
  const Vec3 spot = texel_centre(10, 20, width, height);
  const EnvironmentEmitter env(
      [&](const Vec3& d) { return Vec3(dot(d, spot) > 0.99999f ? 1e4f : 0.01f); }, width);
  const float at_spot = env.pdf_at_infinity(spot);
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj)
      EXPECT_EQ(env.pdf_at_infinity(texel_centre(10 + di, 20 + dj, width, height)), at_spot);
  // Two texels away only the dim sky and the uniform share remain.
  const float uniform = EnvironmentEmitter::kUniformShare / (4.0f * static_cast<float>(kPiD));
  EXPECT_LT(env.pdf_at_infinity(texel_centre(10, 23, width, height)), 1.01f * uniform);
}

TEST(Environment, TableDoesNotDependOnTheThreadCount) {
  std::unique_ptr<EnvironmentEmitter> one, two;
  tbb::task_arena(1).execute([&] { one = std::make_unique<EnvironmentEmitter>(SunSky{}, 256); });
  tbb::task_arena(2).execute([&] { two = std::make_unique<EnvironmentEmitter>(SunSky{}, 256); });
  for (int k = 0; k < 3; ++k) ASSERT_EQ(one->integral()[k], two->integral()[k]);
  for (int i = 0; i < 20000; ++i) {
    Sampler sampler(3, 0, static_cast<uint32_t>(i), 20000);
    const Vec2 u = sampler.get_2d();
    Vec3 d1, d2;
    float p1, p2;
    ASSERT_TRUE(one->sample_direction(u, &d1, &p1));
    ASSERT_TRUE(two->sample_direction(u, &d2, &p2));
    ASSERT_EQ(p1, p2);
    ASSERT_EQ(d1.x, d2.x);
    ASSERT_EQ(d1.y, d2.y);
    ASSERT_EQ(d1.z, d2.z);
  }
}

TEST(Environment, SampledDirectionsFollowThePdf) {
  // Chi-square test over quarters of texels (2 x 2 cells per texel, equal solid angle): the
  // expected count of a cell is N pdf(cell centre) x its solid angle, exact since the density
  // is constant on a texel; it also checks that directions are uniform inside a texel.
  const int width = 32, height = 16, n = 2;
  const EnvironmentEmitter env(lobe_sky, width);
  const int rows = height * n, cols = width * n;
  std::vector<double> expected(static_cast<size_t>(rows) * cols);
  std::vector<double> z_edge(height + 1);
  for (int i = 0; i <= height; ++i) z_edge[i] = std::cos(kPiD * i / height);
  for (int i = 0; i < rows; ++i) {
    // Within texel row i / n: equal steps in z, so every cell has the same solid angle.
    const double zt = z_edge[i / n], zb = z_edge[i / n + 1];
    const double z0 = zt + (zb - zt) * (i % n) / n, z1 = zt + (zb - zt) * (i % n + 1) / n;
    const double zm = 0.5 * (z0 + z1), s = std::sqrt(1.0 - zm * zm);
    for (int j = 0; j < cols; ++j) {
      const double phi = 2.0 * kPiD * (j + 0.5) / cols;
      const Vec3 d(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                   static_cast<float>(zm));
      expected[static_cast<size_t>(i) * cols + j] =
          env.pdf_at_infinity(d) * band_solid_angle(z0, z1, 2.0 * kPiD / cols);
    }
  }
  const int samples = 2000000;
  std::vector<double> observed(expected.size(), 0.0);
  int pdf_mismatches = 0;
  for (int k = 0; k < samples; ++k) {
    Sampler sampler(5, 0, static_cast<uint32_t>(k), samples);
    Vec3 d;
    float pdf;
    ASSERT_TRUE(env.sample_direction(sampler.get_2d(), &d, &pdf));
    ASSERT_NEAR(length(d), 1.0f, 1e-5f);
    const float lookup = env.pdf_at_infinity(d);
    if (std::fabs(lookup - pdf) > 1e-6f * pdf) ++pdf_mismatches;  // only on texel edges
    double phi = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x));
    if (phi < 0.0) phi += 2.0 * kPiD;
    const int col = std::min(cols - 1, static_cast<int>(phi / (2.0 * kPiD) * cols));
    int t = std::min(height - 1,
                     static_cast<int>(std::acos(std::clamp<double>(d.z, -1, 1)) / kPiD * height));
    while (t > 0 && d.z > z_edge[t]) --t;
    while (t + 1 < height && d.z < z_edge[t + 1]) ++t;
    const double f = (z_edge[t] - d.z) / (z_edge[t] - z_edge[t + 1]);
    const int row = t * n + std::clamp(static_cast<int>(f * n), 0, n - 1);
    observed[static_cast<size_t>(row) * cols + col] += 1.0;
  }
  EXPECT_LT(pdf_mismatches, samples / 10000);
  // Cells expecting fewer than 5 samples are pooled into one.
  double chi2 = 0.0, pooled_expected = 0.0, pooled_observed = 0.0, total_p = 0.0;
  int dof = -1;
  for (size_t c = 0; c < expected.size(); ++c) {
    total_p += expected[c];
    const double e = expected[c] * samples;
    if (e < 5.0) {
      pooled_expected += e;
      pooled_observed += observed[c];
      continue;
    }
    chi2 += (observed[c] - e) * (observed[c] - e) / e;
    ++dof;
  }
  if (pooled_expected > 0.0) {
    chi2 +=
        (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++dof;
  }
  EXPECT_NEAR(total_p, 1.0, 1e-5);
  // For ~2000 degrees of freedom chi2 is close to normal with variance 2 dof: 5 sigma.
  EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof)) << "dof " << dof;
  std::printf("[ environment ] chi-square %.1f for %d degrees of freedom\n", chi2, dof);
}

// A large diffuse floor at z = 0 (albedo rho, the only geometry), optionally with `lamps` dim
// point lights below it so direct lighting takes the light tree's path (EmitterSet).
std::shared_ptr<Scene> floor_under(EnvironmentFunction world, int width, int lamps = 0,
                                   const Vec3& albedo = Vec3(0.5f)) {
  auto scene = std::make_shared<Scene>();
  scene->materials.push_back(Material::diffuse(albedo, "floor"));
  add_mesh_instance(scene.get(), make_quad({-100, -100, 0}, {200, 0, 0}, {0, 200, 0}), 0);
  scene->world.radiance = std::move(world);
  scene->world.sample_map_width = width;
  for (int i = 0; i < lamps; ++i) {
    Light l;
    l.name = "dim";
    l.type = LightType::kPoint;
    l.power = 1e-6f;
    l.radius = 0.1f;
    l.light_to_world = Transform::translation(Vec3(static_cast<float>(i), 0.0f, -5.0f));
    scene->lights.push_back(l);
  }
  // Camera 1 above the floor looking straight down with a tiny window.
  const float cam_rows[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1.0f};
  scene->camera.camera_to_world = Transform::from_rows(cam_rows);
  scene->camera.window_min_x = scene->camera.window_min_y = -1e-3f;
  scene->camera.window_max_x = scene->camera.window_max_y = 1e-3f;
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

TEST(Environment, DirectIrradianceUnderALinearSkyIsAnalytic) {
  // Light samples of the table and BSDF samples weighted by MIS, with every emitter sampled
  // and with the light tree (9 lamps): both must give E = pi a + 2 pi b / 3.
  const LinearSky sky;
  for (int lamps : {0, 9}) {
    const auto scene = floor_under(sky, 128, lamps);
    RenderSettings settings;
    const SceneResources resources(*scene, settings, nullptr);
    ASSERT_EQ(resources.emitters().use_tree(), lamps > 8);
    const SurfaceInteraction si = floor_point(*scene, Vec3(0.3f, -0.2f, 0.0f));
    const int n = 40000;
    Vec3 sum(0.0f);
    double sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
      Sampler sampler(3, 1, static_cast<uint32_t>(i), n);
      const Vec3 e = direct_irradiance(resources.context(), si, sampler);
      sum += e;
      sum2 += mean3(e) * mean3(e);
    }
    const Vec3 mean = sum / static_cast<float>(n);
    const double se = std::sqrt(std::max(0.0, sum2 / n - mean3(mean) * mean3(mean)) / n);
    const Vec3 exact = sky.irradiance(1.0f);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(mean[k], exact[k], 5.0 * se + 1e-4 * exact[k])
          << "channel " << k << ", " << lamps << " lamps";
  }
}

TEST(Environment, ShadowCatcherEstimatesSampleTheEnvironment) {
  // The shadow catcher's pair of estimates (light sampling only) under a linear sky with
  // nothing in the way: equal, and both the analytic irradiance (Lambert of albedo pi).
  const LinearSky sky;
  const auto scene = floor_under(sky, 128);
  RenderSettings settings;
  const SceneResources resources(*scene, settings, nullptr);
  const SurfaceInteraction si = floor_point(*scene, Vec3(0.0f));
  Bsdf lambert(si.ns, si.ng, true);
  Lobe lobe;
  lobe.type = LobeType::kLambert;
  lobe.weight = Vec3(kPi);
  lambert.add(lobe);
  const int n = 40000;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(12, 0, static_cast<uint32_t>(i), n);
    Vec3 unshadowed;
    const Vec3 shadowed = direct_radiance_with_and_without_shadows(resources.context(), si, lambert,
                                                                   si.ns, sampler, &unshadowed);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(shadowed[k], unshadowed[k]);
      sum[k] += shadowed[k];
    }
  }
  const Vec3 exact = sky.irradiance(1.0f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / n, exact[k], 0.01 * exact[k]);
}

TEST(Environment, SunIrradianceNoiseWithImportanceSamplingAgainstBsdfSamplingAlone) {
  // Relative RMSE of 64-sample irradiance estimates on a +z plane under a 1e4 sun 0.5 degrees
  // across: with the table (light samples + BSDF samples, MIS) and with cosine-distributed BSDF
  // samples alone (what a world reached only through the BSDF gets: E = pi mean L).
  const SunSky world;
  const double exact = world.irradiance_up();
  // BSDF sampling alone, exactly: the second moment of pi L under cosine sampling is
  // pi (integral of L^2 cos): the sky's a^2 pi + 2 a b (2 pi / 3) + b^2 pi / 2 + c^2 pi / 4,
  // the sun's S^2 pi sin^2(alpha) cos(theta), and their cross term 2 S L_sky(sun) x the same.
  const double a = world.sky.a.x, b = world.sky.b.x, c = world.sky.c.x, S = world.sun_radiance;
  const double sun_cos = kPiD * std::pow(std::sin(world.half_angle), 2) * std::sin(world.elevation);
  const double sky_at_sun = mean3(world.sky(world.sun()));
  const double moment = kPiD * (a * a * kPiD + 2.0 * a * b * 2.0 * kPiD / 3.0 + b * b * kPiD / 2.0 +
                                c * c * kPiD / 4.0 + (S * S + 2.0 * S * sky_at_sun) * sun_cos);
  const int spp = 64;
  const double rmse_bsdf_exact = std::sqrt((moment - exact * exact) / spp) / exact;
  for (int width : {1024, 2048}) {
    const auto scene = floor_under(world, width);
    RenderSettings settings;
    const SceneResources resources(*scene, settings, nullptr);
    const int estimates = 400;
    double se_is = 0.0, se_bsdf = 0.0;
    for (int k = 0; k < estimates; ++k) {
      const SurfaceInteraction si =
          floor_point(*scene, Vec3(0.01f * static_cast<float>(k % 20), 0.01f * (k / 20.0f), 0.0f));
      double is = 0.0, bsdf = 0.0;
      for (int i = 0; i < spp; ++i) {
        Sampler sampler(7, static_cast<uint64_t>(k), static_cast<uint32_t>(i), spp);
        is += mean3(direct_irradiance(resources.context(), si, sampler));
        Sampler cosine(8, static_cast<uint64_t>(k), static_cast<uint32_t>(i), spp);
        bsdf += kPiD * mean3(world(sample_cosine_hemisphere(cosine.get_2d())));
      }
      se_is += (is / spp - exact) * (is / spp - exact);
      se_bsdf += (bsdf / spp - exact) * (bsdf / spp - exact);
    }
    const double rmse_is = std::sqrt(se_is / estimates) / exact;
    const double rmse_bsdf = std::sqrt(se_bsdf / estimates) / exact;
    std::printf(
        "[ environment ] %d-wide map, sun irradiance %.4f, relative RMSE at %d spp: "
        "importance sampled %.4f; BSDF only %.4f measured (the sun is missed), %.2f "
        "exact\n",
        width, exact, spp, rmse_is, rmse_bsdf, rmse_bsdf_exact);
    // The sun covers ~1.5 texels of a 1024-wide map, ~6 of a 2048-wide one: a piecewise-constant
    // table samples the texels it partly covers, which bounds how far the noise can drop.
    EXPECT_LT(rmse_is, width == 1024 ? 0.15 : 0.06);
    EXPECT_LT(rmse_is * 2.0, rmse_bsdf);
    EXPECT_LT(rmse_is * 50.0, rmse_bsdf_exact);
  }
}

std::vector<float> render_image(std::shared_ptr<const Scene> scene,
                                const RenderSettings& settings) {
  RenderSession session(std::move(scene), settings);
  session.start();
  session.wait();
  return session.image();
}

RenderSettings small_settings(int width, int height, int spp, IntegratorType integrator) {
  RenderSettings s;
  s.full_width = s.x1 = width;
  s.full_height = s.y1 = height;
  s.x0 = s.y0 = 0;
  s.samples = spp;
  s.seed = 17;
  s.integrator = integrator;
  s.photons = 20000;
  s.caustic_photons = 10000;
  s.final_gather_rays = 4;
  return s;
}

TEST(Environment, FurnaceWhiteSphereInAUniformEnvironmentFunction) {
  // A convex white (albedo 1) sphere in radiance 1 from every direction, given as a function:
  // each point receives E = pi and reflects 1, as the background is. Ray tracing and photon
  // mapping (direct light by the table with MIS; no indirect light reaches a convex object).
  auto scene = std::make_shared<Scene>();
  scene->materials.push_back(Material::diffuse(Vec3(1.0f), "white"));
  add_mesh_instance(scene.get(), make_uv_sphere(Vec3(0.0f), 1.0f, 96, 48), 0);
  scene->world.radiance = [](const Vec3&) { return Vec3(1.0f); };
  scene->world.sample_map_width = 256;
  scene->camera = make_look_at_camera(Vec3(0, -4, 0), Vec3(0.0f), 0.6f, 1.0f);
  for (IntegratorType integrator : {IntegratorType::kRayTrace, IntegratorType::kPhotonMap}) {
    const std::vector<float> image = render_image(scene, small_settings(16, 16, 64, integrator));
    ASSERT_EQ(image.size(), 16u * 16u * 4u);
    double sum = 0.0;
    for (size_t i = 0; i < image.size(); i += 4)
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(image[i + k], 1.0f, 0.05f) << "pixel " << i / 4;
        sum += image[i + k];
      }
    EXPECT_NEAR(sum / (16 * 16 * 3), 1.0, 0.005) << static_cast<int>(integrator);
  }
}

TEST(Environment, BackgroundAndMirrorReflectionShowTheFunction) {
  // Sky A above the horizon, ground B below. A camera looking down sees B with nothing in the
  // way, and A in a mirror floor; a uniform world colour is ignored once a function is set.
  const Vec3 above(0.25f, 0.5f, 2.0f), below(3.0f, 0.125f, 0.75f);
  auto world = [=](const Vec3& w) { return w.z > 0.0f ? above : below; };
  for (bool mirror : {false, true}) {
    auto scene = floor_under(world, 64);
    scene->world.color = Vec3(7.0f);
    if (mirror) {
      scene->materials[0] = Material::mirror(Vec3(1.0f));
    } else {
      scene->meshes.clear();
      scene->instances.clear();
    }
    const Vec3 expected = mirror ? above : below;
    for (IntegratorType integrator :
         {IntegratorType::kRayTrace, IntegratorType::kPhotonMap, IntegratorType::kRadiosity}) {
      const std::vector<float> image = render_image(scene, small_settings(4, 4, 4, integrator));
      ASSERT_EQ(image.size(), 4u * 4u * 4u);
      for (size_t i = 0; i < image.size(); i += 4)
        for (int k = 0; k < 3; ++k)
          ASSERT_NEAR(image[i + k], expected[k], 1e-5f * expected[k])
              << "mirror " << mirror << ", integrator " << static_cast<int>(integrator);
    }
  }
}

TEST(Environment, ConstantFunctionEmitsWhatTheUniformWorldEmits) {
  const Vec3 c(0.5f, 1.0f, 2.0f);
  const EnvironmentEmitter env([=](const Vec3&) { return c; }, 128);
  const WorldEmitter uniform(c);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(env.integral()[k], 4.0 * kPiD * c[k], 1e-5 * c[k]);
    EXPECT_NEAR(env.power(3.0f)[k], uniform.power(3.0f)[k], 1e-5 * uniform.power(3.0f)[k]);
  }
  // A constant table is uniform: every photon carries exactly the emitter's power.
  for (int i = 0; i < 1000; ++i) {
    Sampler sampler(1, 2, static_cast<uint32_t>(i), 1000);
    EmittedPhoton photon;
    env.sample_le(PhotonFrame{Vec3(0.0f), 3.0f}, 0.5f, sampler.get_2d(), sampler.get_2d(), false,
                  &photon);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(photon.power[k], uniform.power(3.0f)[k], 1e-4 * uniform.power(3.0f)[k]);
  }
}

TEST(Environment, EmittedPhotonsCarryTheIntegralAndTheIrradianceOfAPatch) {
  // Jensen 2001 sec. 5.1: photons entering through the disc of radius R carry
  // L / pdf x pi R^2. Their mean is the power (pi R^2 x the integral of L), and the flux they
  // carry through a small horizontal patch at the centre is E x area from each side.
  const LinearSky sky;
  const EnvironmentEmitter env(sky, 128);
  const float radius = 1.0f, half = 0.1f;
  const int n = 2000000;
  double mean_d[3] = {0, 0, 0}, down_d[3] = {0, 0, 0}, up_d[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(9, 0, static_cast<uint32_t>(i), n);
    const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
    EmittedPhoton photon;
    env.sample_le(PhotonFrame{Vec3(0.0f), radius}, 0.5f, u_pos, u_dir, false, &photon);
    ASSERT_TRUE(is_finite(photon.power));
    for (int k = 0; k < 3; ++k) mean_d[k] += photon.power[k];
    const Ray& r = photon.ray;
    // Every photon starts outside the scene's sphere.
    ASSERT_GE(length(r.origin), radius * 0.999f);
    if (r.direction.z == 0.0f) continue;
    const float t = -r.origin.z / r.direction.z;
    if (!(t > 0.0f)) continue;
    const Vec3 p = r.origin + r.direction * t;
    if (std::fabs(p.x) > half || std::fabs(p.y) > half) continue;
    double* side = r.direction.z < 0.0f ? down_d : up_d;
    for (int k = 0; k < 3; ++k) side[k] += photon.power[k];
  }
  const Vec3 power = env.power(radius);
  const double area = 4.0 * half * half;
  const Vec3 e_top = sky.irradiance(1.0f), e_bottom = sky.irradiance(-1.0f);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(mean_d[k] / n, power[k], 0.003 * power[k]) << "channel " << k;
    // The integral of a + b z + c x over the sphere is 4 pi a.
    EXPECT_NEAR(power[k], kPiD * radius * radius * 4.0 * kPiD * sky.a[k], 1e-4 * power[k]);
    EXPECT_NEAR(down_d[k] / n, e_top[k] * area, 0.03 * e_top[k] * area) << "channel " << k;
    EXPECT_NEAR(up_d[k] / n, e_bottom[k] * area, 0.03 * e_bottom[k] * area) << "channel " << k;
  }
}

TEST(Environment, CausticPhotonsCarryTheFluxThroughTheirTarget) {
  // Photons aimed at a sphere of radius r off the scene's centre: each passes through it, and
  // their mean power is the flux the environment sends through its cross-section,
  // pi r^2 x the integral of L (the same as unaimed photons that land in it).
  const LinearSky sky;
  const EnvironmentEmitter env(sky, 128);
  const BoundingSphere target{Vec3(0.5f, -0.3f, 0.2f), 0.25f};
  const PhotonFrame frame{Vec3(0.1f, 0.0f, 0.0f), 2.0f};
  const float share = env.coverage({target}, frame.radius);
  EXPECT_NEAR(share, 0.25f * 0.25f / 4.0f, 1e-6f);
  const int n = 400000;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(6, 0, static_cast<uint32_t>(i), n);
    const float u_pick = sampler.get_1d();
    const Vec2 u_pos = sampler.get_2d(), u_dir = sampler.get_2d();
    EmittedPhoton photon;
    ASSERT_TRUE(env.sample_le_towards({target}, frame, u_pick, u_pos, u_dir, sampler, &photon));
    const Vec3 to_center = target.center - photon.ray.origin;
    const float along = dot(to_center, photon.ray.direction);
    ASSERT_GT(along, 0.0f);  // starts before the target
    ASSERT_LE(length(to_center - photon.ray.direction * along), target.radius * 1.0001f);
    for (int k = 0; k < 3; ++k) sum[k] += photon.power[k];
  }
  const Vec3 through = env.integral() * (kPi * target.radius * target.radius);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / n, through[k], 0.005 * through[k]);
}

TEST(Environment, PhotonSourcesSplitPowerWithTheEnvironment) {
  // The environment is one more photon source: total power = pi R^2 x the integral (R from
  // the scene's bounds), and the mean power of emitted global photons matches it.
  const LinearSky sky;
  const auto scene = floor_under(sky, 128);
  RenderSettings settings;
  const SceneResources resources(*scene, settings, nullptr);
  const PhotonSources sources(resources.context());
  ASSERT_TRUE(sources.has_global());
  const float r = sources.scene_radius();
  const Vec3 expected = resources.emitters().world()->power(r);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(sources.total_power()[k], 4.0 * kPiD * kPiD * r * r * sky.a[k], 1e-4 * expected[k]);
  const int n = 200000;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(4, 0, static_cast<uint32_t>(i), n);
    EmittedPhoton photon;
    if (!sources.emit_global(sampler, &photon)) continue;
    for (int k = 0; k < 3; ++k) sum[k] += photon.power[k];
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / n, expected[k], 0.01 * expected[k]);
}

TEST(Environment, RadiosityFloorUnderALinearSkyReceivesItsIrradiance) {
  // The radiosity solve lights the floor only by photons the environment shoots: its radiance
  // rho E / pi must come out of sample_le() (directions and powers) right.
  const LinearSky sky;
  const Vec3 albedo(0.5f);
  auto scene = floor_under(sky, 128, 0, albedo);
  // A floor as small as the camera's view keeps the scene's bounding disc (where photons
  // enter) close to it, so most rays land.
  scene->meshes.clear();
  scene->instances.clear();
  add_mesh_instance(scene.get(), make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0);
  RenderSettings settings = small_settings(4, 4, 1, IntegratorType::kRadiosity);
  settings.radiosity_rays = 4000000;
  settings.radiosity_patch_size = 2.0f;  // two triangles: noise averages over the floor
  const std::vector<float> image = render_image(scene, settings);
  const Vec3 e = sky.irradiance(1.0f);
  for (size_t i = 0; i < image.size(); i += 4)
    for (int k = 0; k < 3; ++k) {
      const float expected = albedo[k] * e[k] / kPi;
      EXPECT_NEAR(image[i + k], expected, 0.02f * expected) << "pixel " << i / 4;
    }
}

TEST(Environment, AFlatWorldIsLitByBsdfSamplesAlone) {
  // A node tree that gives one colour everywhere (an RGB node into the Background) is lit as
  // the uniform world is; one texel of another colour keeps the table's light samples.
  const Vec3 grey(0.37f, 0.44f, 0.5f);
  const EnvironmentEmitter flat([&](const Vec3&) { return grey; }, 64);
  EXPECT_TRUE(flat.flat());
  EXPECT_TRUE(flat.flags() & kEmitterBsdfSampledOnly);
  EXPECT_EQ(flat.pdf_li_at_infinity(Vec3(0.0f), Vec3(0, 0, 1)), 0.0f);
  LightSample ls;
  EXPECT_FALSE(flat.sample_li(Vec3(0.0f), LightSampleU{0.0f, Vec2(0.3f, 0.6f)}, nullptr, &ls));
  // Bidirectional estimators (VCM, portals) still sample its table.
  const PhotonFrame frame;
  EXPECT_TRUE(flat.sample_li(Vec3(0.0f), LightSampleU{0.0f, Vec2(0.3f, 0.6f)}, &frame, &ls));
  EXPECT_EQ(flat.radiance_at_infinity(Vec3(0, 0, 1)).x, grey.x);
  const EnvironmentEmitter spotted([&](const Vec3& d) { return d.z > 0.99f ? grey * 2.0f : grey; },
                                   64);
  EXPECT_FALSE(spotted.flat());
  EXPECT_FALSE(spotted.flags() & kEmitterBsdfSampledOnly);
  EXPECT_FALSE(EnvironmentEmitter([](const Vec3&) { return Vec3(0.0f); }, 64).flat());
}

TEST(Environment, CancelStopsTabulating) {
  // With the render already cancelled the function is not evaluated (the table is black and the
  // density uniform); otherwise once per texel.
  std::atomic<int> calls{0};
  auto counted = [&calls](const Vec3&) {
    calls.fetch_add(1, std::memory_order_relaxed);
    return Vec3(1.0f);
  };
  const std::atomic<bool> cancelled{true};
  const EnvironmentEmitter abandoned(counted, 64, 1, &cancelled);
  EXPECT_EQ(calls.load(), 0);
  EXPECT_FLOAT_EQ(abandoned.pdf_at_infinity(Vec3(0, 0, 1)), 1.0f / (4.0f * kPi));
  const std::atomic<bool> running{false};
  const EnvironmentEmitter built(counted, 64, 1, &running);
  EXPECT_EQ(calls.load(), 64 * 32);
}

TEST(Environment, BadFunctionValuesAndMapWidthAreSanitizedWithAWarning) {
  // NaN, infinite and negative radiance count as 0; a map width out of range is clamped, with
  // a warning, and direct lighting stays finite.
  auto broken = [](const Vec3& w) {
    if (w.x > 0.5f) return Vec3(NAN, 1.0f, 1.0f);
    if (w.y > 0.5f) return Vec3(INFINITY, -1.0f, 2.0f);
    return Vec3(1.0f);
  };
  auto scene = floor_under(broken, 3);
  std::vector<std::string> warnings;
  RenderSettings settings;
  const SceneResources resources(*scene, settings, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("sample map width 3"), std::string::npos) << warnings[0];
  const Emitter* env = resources.emitters().world();
  ASSERT_NE(env, nullptr);
  const Vec3 l = env->radiance_at_infinity(normalize(Vec3(0.0f, 1.0f, 0.1f)));
  EXPECT_EQ(l.x, 0.0f);
  EXPECT_EQ(l.y, 0.0f);
  EXPECT_EQ(l.z, 2.0f);
  const SurfaceInteraction si = floor_point(*scene, Vec3(0.0f));
  for (int i = 0; i < 1000; ++i) {
    Sampler sampler(2, 0, static_cast<uint32_t>(i), 1000);
    ASSERT_TRUE(is_finite(direct_irradiance(resources.context(), si, sampler)));
  }
}

}  // namespace
}  // namespace environment_test
}  // namespace photon

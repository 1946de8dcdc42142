#include "photon/session/progressive_session.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <thread>
#include <vector>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/timing_slack.h"

namespace photon {
namespace progressive_session_test {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

RenderSettings settings(IntegratorType type, int size, int spp) {
  RenderSettings s;
  s.integrator = type;
  s.full_width = s.full_height = size;
  s.x0 = s.y0 = 0;
  s.x1 = s.y1 = size;
  s.samples = spp;
  s.seed = 5;
  s.photons = 20000;
  s.caustic_photons = 10000;
  s.final_gather_rays = 4;
  s.threads = 2;
  return s;
}

std::vector<float> final_render(std::shared_ptr<const Scene> scene, const RenderSettings& s) {
  RenderSession session(std::move(scene), s);
  session.start();
  session.wait();
  return session.image();
}

// The progressive image once all `s.samples` samples are in, rendered in passes of growing
// size (1, 1, 2, 4, ... samples) that run on other threads than a tile render.
ProgressiveImage progressive(std::shared_ptr<const Scene> scene, const RenderSettings& s) {
  ProgressiveSession session(std::move(scene), s);
  session.start();
  EXPECT_EQ(session.wait_for_samples(s.samples, 120.0), s.samples);
  EXPECT_TRUE(session.converged());
  return session.image();
}

// N samples accumulated in passes are the final render of N samples: each pixel's sum adds
// the same (seed, pixel, sample) samples in the same order.
void expect_matches_final(IntegratorType type, bool spectral = false) {
  auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings s = settings(type, 48, 12);
  s.spectral = spectral;
  const std::vector<float> reference = final_render(scene, s);
  const ProgressiveImage image = progressive(scene, s);
  ASSERT_EQ(image.rgba.size(), reference.size());
  EXPECT_EQ(image.samples, 12);
  EXPECT_FALSE(image.quick);
  double mean = 0.0;
  for (size_t i = 0; i < reference.size(); ++i) {
    ASSERT_NEAR(image.rgba[i], reference[i], 1e-6f * std::max(1.0f, std::fabs(reference[i])))
        << "float " << i;
    mean += reference[i];
  }
  EXPECT_GT(mean / reference.size(), 0.01);  // not two black images
}

TEST(ProgressiveSession, PassesEqualFinalRenderRayTrace) {
  expect_matches_final(IntegratorType::kRayTrace);
}

TEST(ProgressiveSession, PassesEqualFinalRenderPhotonMap) {
  expect_matches_final(IntegratorType::kPhotonMap);
}

// The viewport in spectral mode: a sample's wavelengths depend on its index only.
TEST(ProgressiveSession, PassesEqualFinalRenderSpectral) {
  expect_matches_final(IntegratorType::kPhotonMap, true);
}

// A frame wide enough for the coarse first pass (every 3rd pixel): it is only shown, never
// accumulated, so the passes still add up to the final render.
TEST(ProgressiveSession, CoarseFirstPassLeavesPassesEqualFinalRender) {
  auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings s = settings(IntegratorType::kPhotonMap, 410, 3);
  s.full_height = s.y1 = 30;
  const std::vector<float> reference = final_render(scene, s);
  const ProgressiveImage image = progressive(scene, s);
  ASSERT_EQ(image.rgba.size(), reference.size());
  for (size_t i = 0; i < reference.size(); ++i)
    ASSERT_NEAR(image.rgba[i], reference[i], 1e-6f * std::max(1.0f, std::fabs(reference[i])));
}

// A view change restarts from sample 0 with the new camera and frame; the result is the final
// render of that view, not a blend of both.
TEST(ProgressiveSession, NewViewRestartsAccumulation) {
  auto scene = std::make_shared<Scene>(make_cornell_box());
  const RenderSettings s = settings(IntegratorType::kRayTrace, 40, 8);
  ProgressiveSession session(scene, s);
  session.start();
  ASSERT_GE(session.wait_for_samples(1, 60.0), 1);

  auto moved = std::make_shared<Scene>(*scene);
  moved->camera = make_look_at_camera({0.3f, 0.2f, 3.0f}, {0.0f, 0.0f, 0.0f}, 0.7f, 1.0f);
  RenderSettings s2 = s;
  s2.full_width = 32;
  s2.full_height = 24;
  s2.x0 = 4, s2.y0 = 2, s2.x1 = 28, s2.y1 = 20;  // a border
  ProgressiveView view;
  view.camera = moved->camera;
  view.full_width = s2.full_width;
  view.full_height = s2.full_height;
  view.x0 = s2.x0, view.y0 = s2.y0, view.x1 = s2.x1, view.y1 = s2.y1;
  const uint64_t serial = session.set_view(view);
  EXPECT_EQ(session.samples_done(), 0);
  ASSERT_EQ(session.wait_for_samples(s.samples, 60.0), s.samples);
  const ProgressiveImage image = session.image();
  EXPECT_EQ(image.view_serial, serial);
  EXPECT_EQ(image.width, 24);
  EXPECT_EQ(image.height, 18);
  const std::vector<float> reference = final_render(moved, s2);
  ASSERT_EQ(image.rgba.size(), reference.size());
  for (size_t i = 0; i < reference.size(); ++i)
    ASSERT_NEAR(image.rgba[i], reference[i], 1e-6f * std::max(1.0f, std::fabs(reference[i])));
}

// The quick first pass shows an image long before photon tracing ends.
TEST(ProgressiveSession, QuickFirstImageBeforePhotonMaps) {
  RenderSettings s = settings(IntegratorType::kPhotonMap, 64, 4);
  s.photons = 50000000;  // minutes of tracing
  s.photon_time = 0.0f;
  ProgressiveSession session(std::make_shared<Scene>(make_cornell_box()), s);
  const auto t0 = Clock::now();
  session.start();
  while (!session.image().quick && seconds_since(t0) < 20.0)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const ProgressiveImage image = session.image();
  ASSERT_TRUE(image.quick);
  EXPECT_TRUE(session.preparing());  // the photons are still being traced
  EXPECT_LT(session.first_image_seconds(), 2.0 * timing_slack());
  double mean = 0.0;
  for (float v : image.rgba) mean += v;
  EXPECT_GT(mean / image.rgba.size(), 0.01);
  EXPECT_EQ(session.samples_done(), 0);  // the quick look is not a sample of the real image
}

double mean_of(const ProgressiveImage& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    sum += image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2];
  return sum / (0.75 * image.rgba.size());
}

// Whether an integrator has a coarse first look, and its settings.
bool coarse_photon_settings(const RenderSettings& s, RenderSettings* coarse) {
  return make_integrator(s.integrator)->coarse_settings(s, coarse);
}

TEST(ProgressiveSession, CoarsePhotonSettingsTakeASixteenthOfLargeMapsOnly) {
  RenderSettings s = settings(IntegratorType::kPhotonMap, 16, 1);
  RenderSettings coarse;
  s.photons = 20000;  // comes at once: no coarse map
  EXPECT_FALSE(coarse_photon_settings(s, &coarse));
  s.photons = 1600000;
  s.caustic_photons = 320000;
  ASSERT_TRUE(coarse_photon_settings(s, &coarse));
  EXPECT_EQ(coarse.photons, 100000u);
  EXPECT_EQ(coarse.caustic_photons, 20000u);
  EXPECT_EQ(coarse.samples, s.samples);
  s.photons = 20000;
  s.photon_time = 2.0f;  // a time budget: a sixteenth of it
  ASSERT_TRUE(coarse_photon_settings(s, &coarse));
  EXPECT_FLOAT_EQ(coarse.photon_time, 0.125f);
  s.integrator = IntegratorType::kSppm;  // its own first iteration is its first look
  EXPECT_FALSE(coarse_photon_settings(s, &coarse));
  s.integrator = IntegratorType::kRadiosity;
  EXPECT_FALSE(coarse_photon_settings(s, &coarse));
  s.integrator = IntegratorType::kRayTrace;
  EXPECT_FALSE(coarse_photon_settings(s, &coarse));
}

// After the direct-light look, a pass over a coarse photon map shows the indirect light while
// the full map is traced; the converged image is the final render's as before.
TEST(ProgressiveSession, CoarsePhotonMapShowsIndirectLightBeforeTheFullMap) {
  auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings s = settings(IntegratorType::kPhotonMap, 48, 2);
  s.photons = 96000;  // the coarse map's 6,000 come several times faster
  s.caustic_photons = 0;
  ProgressiveSession session(scene, s);
  session.start();
  ProgressiveImage direct, coarse;
  const auto t0 = Clock::now();
  while (!session.converged() && seconds_since(t0) < 120.0) {
    const ProgressiveImage image = session.image();
    if (image.quick && !image.coarse_photons && image.step == 1 && direct.rgba.empty())
      direct = image;
    if (image.coarse_photons && coarse.rgba.empty()) {
      coarse = image;
      EXPECT_TRUE(session.preparing());  // the full map is still being traced
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(session.converged());
  ASSERT_FALSE(direct.rgba.empty());
  ASSERT_FALSE(coarse.rgba.empty());
  EXPECT_TRUE(coarse.quick);
  const ProgressiveImage full = session.image();
  const double d = mean_of(direct), c = mean_of(coarse), f = mean_of(full);
  std::printf("image means: direct light %.4f, coarse photon map %.4f, full %.4f\n", d, c, f);
  EXPECT_GT(c, d * 1.1);  // the indirect light of the box's walls
  EXPECT_LT(std::fabs(c - f), 0.05 * f);
  const std::vector<float> reference = final_render(scene, s);
  ASSERT_EQ(full.rgba.size(), reference.size());
  for (size_t i = 0; i < reference.size(); ++i)
    ASSERT_NEAR(full.rgba[i], reference[i], 1e-6f * std::max(1.0f, std::fabs(reference[i])));
}

// Cancel (the viewport closed, the scene changed) stops a pass within a row of samples.
TEST(ProgressiveSession, CancelLatency) {
  RenderSettings s = settings(IntegratorType::kPhotonMap, 128, 1 << 16);
  s.irradiance_cache = false;
  s.final_gather_rays = 64;
  ProgressiveSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  ASSERT_GE(session.wait_for_samples(2, 120.0), 2);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  const auto t0 = Clock::now();
  session.cancel();
  session.wait();
  const double latency = seconds_since(t0);
  std::printf("progressive cancel: %.1f ms\n", latency * 1e3);
  EXPECT_TRUE(session.finished());
  EXPECT_LT(latency, 0.1 * timing_slack());
}

// A converged session sleeps (no CPU) until a new view comes.
TEST(ProgressiveSession, StopsAtTargetSamples) {
  const RenderSettings s = settings(IntegratorType::kRayTrace, 16, 3);
  ProgressiveSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  ASSERT_EQ(session.wait_for_samples(3, 60.0), 3);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_TRUE(session.converged());
  EXPECT_EQ(session.image().samples, 3);
  EXPECT_FALSE(session.finished());
  EXPECT_FLOAT_EQ(session.progress(), 1.0f);
}

}  // namespace
}  // namespace progressive_session_test
}  // namespace photon

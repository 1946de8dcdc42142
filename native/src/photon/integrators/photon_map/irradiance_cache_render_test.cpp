// The irradiance cache inside whole renders: thread independence and the noise it removes.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace irradiance_cache_render_test {
namespace {

RenderSettings cornell_settings(int size, int spp, uint64_t seed) {
  RenderSettings s;
  s.full_width = s.full_height = size;
  s.x1 = s.y1 = size;
  s.samples = spp;
  s.seed = seed;
  s.photons = 20000;
  s.caustic_photons = 0;
  s.final_gather_rays = 8;
  s.irradiance_cache = true;
  return s;
}

struct Output {
  std::vector<float> rgba;
  double records = 0.0;
};

Output render(const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  session.wait();
  Output out{session.image()};
  if (const auto& cache = session.stats().integrator.irradiance_cache)
    out.records = static_cast<double>(cache->records);
  return out;
}

// Per-pixel relative noise of two renders with different seeds: rms(a - b) / sqrt(2) / mean.
double relative_noise(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0.0, mean = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) continue;
    diff += (a[i] - b[i]) * double(a[i] - b[i]);
    mean += 0.5 * (a[i] + b[i]);
    ++n;
  }
  return std::sqrt(diff / n / 2.0) / (mean / n);
}

TEST(IrradianceCacheRender, CachedCornellBoxDoesNotDependOnThreadsOrTiles) {
  RenderSettings one = cornell_settings(40, 2, 7);
  one.threads = 1;
  one.tile_size = 64;
  RenderSettings two = one;
  two.threads = 2;
  two.tile_size = 7;
  const Output a = render(one), b = render(two);
  EXPECT_GT(a.records, 50.0);
  EXPECT_EQ(a.records, b.records);
  EXPECT_TRUE(a.rgba == b.rgba);  // bit-identical
}

TEST(IrradianceCacheRender, CacheReducesPixelNoise) {
  // Few samples, so the per-sample final gather is noisy; the direct light's noise is the
  // same in both, so the cache's gain shows in the combined image.
  RenderSettings s = cornell_settings(48, 4, 1);
  RenderSettings t = s;
  t.seed = 2;
  const double cached = relative_noise(render(s).rgba, render(t).rgba);
  s.irradiance_cache = t.irradiance_cache = false;
  const double uncached = relative_noise(render(s).rgba, render(t).rgba);
  std::printf("relative pixel noise: %.4f with the cache, %.4f without\n", cached, uncached);
  EXPECT_LT(cached, 0.75 * uncached);
}

TEST(IrradianceCacheRender, CacheKeepsTheMeanOfPerSampleGathering) {
  // Interpolation must not bias the image: the means agree within the photon-map noise.
  RenderSettings s = cornell_settings(48, 8, 3);
  const Output cached = render(s);
  s.irradiance_cache = false;
  const Output plain = render(s);
  double ma = 0.0, mb = 0.0;
  for (size_t i = 0; i < cached.rgba.size(); i += 4) ma += cached.rgba[i], mb += plain.rgba[i];
  EXPECT_NEAR(ma / mb, 1.0, 0.01);
}

TEST(IrradianceCacheRender, CancelDuringTheCacheBuildStopsPromptly) {
  RenderSettings s = cornell_settings(1024, 4, 1);
  s.final_gather_rays = 64;  // 4096 rays per record: far too long a build for the test
  s.threads = 2;
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  const auto t0 = std::chrono::steady_clock::now();
  while (session.status().rfind("Irradiance cache", 0) != 0 && !session.finished() &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(session.status().rfind("Irradiance cache", 0), 0u) << session.status();
  session.cancel();
  const auto t1 = std::chrono::steady_clock::now();
  session.wait();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), 2.0);
  EXPECT_TRUE(session.cancelled());
  EXPECT_EQ(session.status(), "Cancelled");
}

}  // namespace
}  // namespace irradiance_cache_render_test
}  // namespace photon

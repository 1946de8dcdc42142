// Cancellation latency of every native stage: a cancel issued at a random moment while the
// stage runs (each stage given > 1 s of work) must end it within kLatencyBound. Stages that
// only run inside a full render are reached through a RenderSession and recognised by its
// status; the kd-tree and radiance-cache builds are timed on synthetic data of a size that
// takes seconds (a render would spend far longer tracing the photons first).
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <string>
#include <thread>

#include "photon/base/rng.h"
#include "photon/integrators/photon_map/photon_map.h"
#include "photon/integrators/photon_map/radiance_cache.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/timing_slack.h"

namespace photon {
namespace cancel_latency_test {
namespace {

using Clock = std::chrono::steady_clock;
// Every stage polls at least every 100 ms; the rest is scheduling slack on a loaded machine.
const double kLatencyBound = (0.1 + 0.1) * timing_slack();

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A random moment in the first `spread` seconds of a stage.
std::chrono::milliseconds random_delay(int spread_ms) {
  static std::mt19937 rng(std::random_device{}());
  return std::chrono::milliseconds(std::uniform_int_distribution<int>(0, spread_ms)(rng));
}

RenderSettings cornell_settings(int size, int spp) {
  RenderSettings s;
  s.full_width = s.x1 = size;
  s.full_height = s.y1 = size;
  s.samples = spp;
  s.seed = 5;
  s.threads = 2;
  s.photons = 20000;
  s.caustic_photons = 0;
  s.final_gather_rays = 4;
  return s;
}

// Starts a render, waits until its status begins with `stage`, cancels at a random moment of
// the stage's first `spread_ms` and returns the seconds until the session finished.
double cancel_during(const RenderSettings& settings, const std::string& stage, int spread_ms) {
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), settings);
  session.start();
  const auto limit = Clock::now() + std::chrono::seconds(300);
  while (session.status().rfind(stage, 0) != 0) {
    if (session.finished() || Clock::now() > limit) {
      ADD_FAILURE() << "the render never reached '" << stage << "' (status " << session.status()
                    << ")";
      return 0.0;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::this_thread::sleep_for(random_delay(spread_ms));
  // The stage must still be running, or the test measures nothing.
  EXPECT_EQ(session.status().rfind(stage, 0), 0u)
      << "stage ended before the cancel: " << session.status();
  const auto t0 = Clock::now();
  session.cancel();
  session.wait();
  const double latency = seconds_since(t0);
  EXPECT_TRUE(session.finished());
  EXPECT_EQ(session.status(), "Cancelled");
  std::printf("cancel during '%s': %.1f ms\n", stage.c_str(), latency * 1e3);
  return latency;
}

TEST(CancelLatency, PhotonTracing) {
  RenderSettings s = cornell_settings(32, 1);
  s.photons = 50000000;  // minutes of tracing
  EXPECT_LT(cancel_during(s, "Tracing photons", 500), kLatencyBound);
}

TEST(CancelLatency, RadiancePrecompute) {
  RenderSettings s = cornell_settings(32, 1);
  s.photons = 400000;  // ~190k radiance estimates of 100 photons: seconds
  s.irradiance_cache = false;
  EXPECT_LT(cancel_during(s, "Precomputing radiance", 500), kLatencyBound);
}

TEST(CancelLatency, IrradianceCacheBuild) {
  RenderSettings s = cornell_settings(256, 1);
  s.final_gather_rays = 256;  // 16384 rays per record, thousands of records
  EXPECT_LT(cancel_during(s, "Irradiance cache", 500), kLatencyBound);
}

TEST(CancelLatency, PixelPassKeepsFinishedTiles) {
  RenderSettings s = cornell_settings(256, 256);
  s.irradiance_cache = false;
  s.final_gather_rays = 16;
  s.tile_size = 16;
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  std::vector<Tile> tiles = session.take_tiles(120.0);
  ASSERT_FALSE(tiles.empty());
  std::this_thread::sleep_for(random_delay(300));
  const auto t0 = Clock::now();
  session.cancel();
  session.wait();
  const double latency = seconds_since(t0);
  std::printf("cancel during 'Rendering': %.1f ms\n", latency * 1e3);
  EXPECT_LT(latency, kLatencyBound);
  for (Tile& t : session.take_tiles(0.0)) tiles.push_back(std::move(t));
  // Every tile handed over is in the image, and the image holds nothing else.
  const std::vector<float> image = session.image();
  std::vector<float> expected(image.size(), 0.0f);
  for (const Tile& t : tiles)
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width * 4; ++x)
        expected[(static_cast<size_t>(t.y + y) * s.full_width + t.x) * 4 + x] =
            t.rgba[static_cast<size_t>(y) * t.width * 4 + x];
  EXPECT_TRUE(image == expected);
  EXPECT_LT(tiles.size(), 256u);  // cancelled before the end
}

// Photons spread over a unit cube, as many as a 100M-photon render stores in a room.
std::vector<Photon> random_photons(size_t n) {
  std::vector<Photon> photons(n);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t h = mix64(i + 1);
    const Vec3 p((h & 0xFFFFF) / 1048576.0f, ((h >> 20) & 0xFFFFF) / 1048576.0f,
                 ((h >> 40) & 0xFFFFF) / 1048576.0f);
    photons[i] = Photon::make(p, Vec3(0, 0, -1), Vec3(1.0f), kPhotonIndirect, Vec3(0, 0, 1));
  }
  return photons;
}

// Runs `build` on a thread, cancels after a random delay, returns the seconds from the cancel
// to the end of `build`, and checks that the build was still running then.
template <typename Build>
double cancel_build(Build build, int spread_ms) {
  std::atomic<bool> cancel{false}, done{false};
  std::thread worker([&] {
    build(&cancel);
    done = true;
  });
  std::this_thread::sleep_for(random_delay(spread_ms));
  EXPECT_FALSE(done.load()) << "the build ended before the cancel";
  const auto t0 = Clock::now();
  cancel = true;
  worker.join();
  return seconds_since(t0);
}

TEST(CancelLatency, PhotonMapBuild) {
  std::vector<Photon> photons = random_photons(20000000);  // 400 MB, seconds to balance
  const double latency = cancel_build(
      [&](const std::atomic<bool>* cancel) {
        const PhotonMap map(std::move(photons), cancel);
        EXPECT_TRUE(map.empty());  // a cancelled build leaves no half-balanced tree
      },
      500);
  std::printf("cancel during the kd-tree build: %.1f ms\n", latency * 1e3);
  EXPECT_LT(latency, kLatencyBound);
}

TEST(CancelLatency, RadianceCacheBuild) {
  std::vector<RadianceRecord> records(4000000);  // 400 MB
  for (size_t i = 0; i < records.size(); ++i) {
    const uint64_t h = mix64(i + 7);
    records[i].p = Vec3((h & 0xFFFF) / 65536.0f, ((h >> 16) & 0xFFFF) / 65536.0f, 0.0f);
    records[i].n = Vec3(0, 0, 1);
  }
  const double latency = cancel_build(
      [&](const std::atomic<bool>* cancel) {
        const RadianceCache cache(std::move(records), 0.001f, cancel);
        EXPECT_TRUE(cache.empty());
      },
      300);
  std::printf("cancel during the radiance-cache build: %.1f ms\n", latency * 1e3);
  EXPECT_LT(latency, kLatencyBound);
}

}  // namespace
}  // namespace cancel_latency_test
}  // namespace photon

#include "photon/integrators/photon_map/photon_memory.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>

#include "photon/integrators/photon_map/photon_map.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace photon_memory_test {
namespace {

TEST(PhotonMemory, ParsesMemAvailable) {
  const std::string meminfo =
      "MemTotal:       24000000 kB\nMemFree:         2000000 kB\nMemAvailable:   "
      "21000000 kB\nBuffers:           1000 kB\n";
  EXPECT_EQ(parse_mem_available(meminfo), 21000000ull * 1024);
  EXPECT_EQ(parse_mem_available("MemTotal: 5 kB\n"), 0u);
  EXPECT_GT(available_memory_bytes(), 0u);  // Linux has /proc/meminfo
}

PhotonMemoryRequest cornell_like(uint64_t global, uint64_t caustic) {
  PhotonMemoryRequest r;
  r.global_photons = global;
  r.caustic_photons = caustic;
  r.global_stored_per_emitted = 1.9;
  r.caustic_stored_per_emitted = 0.5;
  r.gather_points_per_emitted = 1.9 / 4;
  r.irradiance_pixels = 1920 * 1080;
  return r;
}

TEST(PhotonMemory, PeakGrowsWithTheStoredPhotons) {
  PhotonMemoryRequest small = cornell_like(1000000, 0), big = cornell_like(2000000, 0);
  small.irradiance_pixels = big.irradiance_pixels = 0;  // then one phase is the peak
  PhotonMemoryRequest none = small;
  none.global_photons = 0;
  // Affine in the counts; at least the photons themselves (20 bytes each).
  const double fixed = photon_peak_bytes(none);
  EXPECT_NEAR(photon_peak_bytes(big) - fixed, 2.0 * (photon_peak_bytes(small) - fixed), 1.0);
  EXPECT_GT(photon_peak_bytes(small) - fixed, 1.9e6 * sizeof(Photon));
  PhotonMemoryRequest no_gather = small;
  no_gather.radiance_records = false;
  EXPECT_LT(photon_peak_bytes(no_gather), photon_peak_bytes(small));
}

TEST(PhotonMemory, RequestOverTheBudgetIsScaledDownToFit) {
  const PhotonMemoryRequest request = cornell_like(100000000, 20000000);
  const double requested = photon_peak_bytes(request);
  const PhotonMemoryPlan fits = plan_photon_memory(request, 2.0 * requested);
  EXPECT_EQ(fits.scale, 1.0);
  EXPECT_EQ(fits.global_photons, request.global_photons);
  EXPECT_EQ(fits.caustic_photons, request.caustic_photons);

  const double budget = 0.1 * requested;
  const PhotonMemoryPlan plan = plan_photon_memory(request, budget);
  EXPECT_LE(plan.scale, 0.1001);
  EXPECT_GT(plan.scale, 0.05);
  EXPECT_LE(plan.planned_bytes, budget);
  EXPECT_GT(plan.planned_bytes, 0.99 * budget);
  EXPECT_EQ(plan.requested_bytes, requested);
  // The ratio of global to caustic photons is kept.
  EXPECT_NEAR(static_cast<double>(plan.global_photons) / plan.caustic_photons, 5.0, 1e-3);
  // Unknown available memory: no scaling.
  EXPECT_EQ(plan_photon_memory(request, 0.0).scale, 1.0);
}

TEST(PhotonMemory, RenderScalesPhotonsDownAndWarns) {
  RenderSettings s;
  s.full_width = s.x1 = 32;
  s.full_height = s.y1 = 32;
  s.samples = 1;
  s.threads = 2;
  s.photons = 50000000;  // ~8 GB at the peak
  s.caustic_photons = 0;
  s.final_gather_rays = 4;
  s.memory_limit = 1e-4f;  // a few MB of the available memory
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  session.wait();
  ASSERT_EQ(session.status(), "Done");
  bool warned = false;
  for (const std::string& w : session.warnings())
    if (w.rfind("Photon memory: 50,000,000 global", 0) == 0 &&
        w.find("tracing ") != std::string::npos)
      warned = true;
  EXPECT_TRUE(warned) << (session.warnings().empty() ? "no warnings" : session.warnings()[0]);
  const PrepareStats& prepared = session.stats().integrator;
  ASSERT_TRUE(prepared.photon_map.has_value());
  ASSERT_TRUE(prepared.photon_memory.has_value());
  const double emitted = static_cast<double>(prepared.photon_map->photons_emitted);
  const double estimate = prepared.photon_memory->estimate_bytes;
  const double available = prepared.photon_memory->available_bytes;
  EXPECT_GT(emitted, 0.0);
  EXPECT_LT(emitted, 50000000.0);
  EXPECT_LE(estimate, 1e-4 * available * 1.0001);
  // The image is still lit.
  double sum = 0.0;
  for (float v : session.image()) sum += v;
  EXPECT_GT(sum, 0.0);
}

TEST(RenderSession, HugeThreadCountsAreClampedWithAWarningAndRenderTheSameImage) {
  RenderSettings s;
  s.full_width = s.x1 = 24;
  s.full_height = s.y1 = 24;
  s.samples = 2;
  s.seed = 3;
  s.photons = 20000;
  s.caustic_photons = 0;
  s.final_gather_rays = 4;
  s.threads = 2;
  const auto scene = std::make_shared<Scene>(make_cornell_box());
  auto render = [&](int threads, std::vector<std::string>* warnings, int* used) {
    RenderSettings t = s;
    t.threads = threads;
    RenderSession session(scene, t);
    session.start();
    session.wait();
    *warnings = session.warnings();
    *used = session.stats().threads;
    return session.image();
  };
  std::vector<std::string> warnings;
  int used = 0;
  const std::vector<float> reference = render(2, &warnings, &used);
  EXPECT_TRUE(warnings.empty());
  for (int threads : {65537, 100000, 2147483647}) {
    for (int repeat = 0; repeat < 2; ++repeat) {  // twice in a row crashed once
      const std::vector<float> image = render(threads, &warnings, &used);
      EXPECT_TRUE(image == reference) << threads << " threads";
      ASSERT_EQ(warnings.size(), 1u) << threads << " threads";
      EXPECT_EQ(warnings[0].rfind("threads = " + std::to_string(threads) + " is more than", 0), 0u)
          << warnings[0];
      EXPECT_LE(used, 4 * static_cast<int>(std::thread::hardware_concurrency()));
      EXPECT_GE(used, 1);
    }
  }
  EXPECT_LE(arena_threads(2147483647), 4 * static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace
}  // namespace photon_memory_test
}  // namespace photon

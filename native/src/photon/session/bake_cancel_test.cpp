// Cancelling a running BakeSession: every stage (photon tracing, the irradiance cache among the
// points, shading) polls the cancel flag every few milliseconds, so Esc and Ctrl-C stop a bake
// of millions of points at once.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>

#include "photon/session/bake.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/timing_slack.h"

namespace photon {
namespace bake_cancel_test {
namespace {

using Clock = std::chrono::steady_clock;

// Many points spread over every triangle of the Cornell box.
std::vector<BakePoint> dense_points(const Scene& scene, size_t per_triangle) {
  std::vector<BakePoint> points;
  for (uint32_t instance = 0; instance < scene.instances.size(); ++instance) {
    const size_t triangles = scene.meshes[scene.instances[instance].mesh].triangle_count();
    for (uint32_t t = 0; t < triangles; ++t)
      for (size_t k = 0; k < per_triangle; ++k) {
        BakePoint p;
        p.instance = instance;
        p.triangle = t;
        // A deterministic spread over the triangle (R2 sequence folded into it).
        float u = static_cast<float>(std::fmod(0.7548776662 * (k + 1), 1.0));
        float v = static_cast<float>(std::fmod(0.5698402910 * (k + 1), 1.0));
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        p.u = u;
        p.v = v;
        points.push_back(p);
      }
  }
  return points;
}

// Starts a bake, waits until `ready` says the stage to interrupt runs, cancels; returns the
// seconds from cancel() to the session's end (and the stage it was in).
template <typename Ready>
double cancel_latency(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
                      const std::vector<BakePoint>& points, Ready ready, std::string* stage) {
  BakeSession session(scene, settings, BakeOptions{}, points);
  session.start();
  const auto started = Clock::now();
  while (!ready(session) && !session.finished() &&
         Clock::now() - started < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_FALSE(session.finished()) << "the bake ended before the stage was reached";
  *stage = session.status();
  const auto t0 = Clock::now();
  session.cancel();
  while (!session.finished() && Clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const double latency = std::chrono::duration<double>(Clock::now() - t0).count();
  session.wait();
  EXPECT_TRUE(session.result().cancelled);
  return latency;
}

TEST(BakeCancel, EveryStageStopsWithinHalfASecond) {
  auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings settings;
  settings.integrator = IntegratorType::kPhotonMap;
  settings.samples = 64;
  settings.photons = 300000;
  settings.final_gather_rays = 16;
  // Sanitized code is several times slower (timing_slack()): a fraction of the points keeps
  // every stage as long as the plain build's, and the wait for the shading stage short.
  const size_t per_triangle = static_cast<size_t>(20000 / timing_slack());
  const std::vector<BakePoint> points = dense_points(*scene, per_triangle);
  ASSERT_GT(points.size(), 300000u / timing_slack());
  auto in_stage = [](const char* prefix) {
    return [prefix](const BakeSession& s) { return s.status().rfind(prefix, 0) == 0; };
  };
  struct Case {
    const char* name;
    std::function<bool(const BakeSession&)> ready;
    size_t photons;  // only photon tracing needs many: the later stages wait for it
  };
  const Case cases[] = {
      {"start", [](const BakeSession&) { return true; }, 300000},
      {"photon tracing", in_stage("Tracing photons"), 300000},
      {"irradiance cache among the points", in_stage("Irradiance cache"), 20000},
      {"shading", [](const BakeSession& s) { return !s.preparing() && s.progress() > 0.01f; },
       20000},
  };
  for (const Case& c : cases) {
    std::string stage;
    RenderSettings case_settings = settings;
    case_settings.photons = c.photons;
    const double latency = cancel_latency(scene, case_settings, points, c.ready, &stage);
    // Stages poll every few ms; the bound leaves room for a machine shared with other jobs.
    EXPECT_LT(latency, 0.5 * timing_slack()) << c.name << " ('" << stage << "')";
    std::printf("cancel during %s ('%s'): stopped in %.1f ms\n", c.name, stage.c_str(),
                1000.0 * latency);
  }
}

}  // namespace
}  // namespace bake_cancel_test
}  // namespace photon

// The Job base that runs renders and bakes: cancellation latency, an exception in the work
// becoming an error status, progress that never goes back while work units are counted, and the
// integrator capabilities the sessions and the add-on ask instead of testing types.
#include "photon/session/job.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "photon/integrators/registry.h"
#include "photon/session/bake.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/timing_slack.h"

namespace photon {
namespace job_test {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Work given as a function of the job, so each test says what its work does.
class TestJob : public Job {
 public:
  explicit TestJob(std::function<void(TestJob&)> work, size_t units = 0)
      : Job("Test"), work_(std::move(work)) {
    set_work_total(units);
  }
  ~TestJob() override { stop_worker(); }

  // The protected helpers, for the work functions below.
  using Job::cancel_flag;
  using Job::prepare_control;
  using Job::set_preparing;
  using Job::set_status;
  using Job::work_done;

 private:
  void run() override { work_(*this); }
  std::function<void(TestJob&)> work_;
};

// Waits for the job to finish, at most `limit` seconds; returns the seconds waited.
double wait_finished(const Job& job, double limit) {
  const auto t0 = Clock::now();
  while (!job.finished() && seconds_since(t0) < limit)
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  return seconds_since(t0);
}

TEST(Job, CancelEndsWorkThatPollsTheFlagPromptly) {
  // Work that would take a minute, polling the flag each millisecond as the stages do.
  TestJob job([](TestJob& self) {
    self.set_status("Working");
    const auto t0 = Clock::now();
    while (!self.cancel_flag() && seconds_since(t0) < 60.0)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  job.start();
  while (job.status() != "Working") std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(job.finished());
  const auto t0 = Clock::now();
  job.cancel();
  const double latency = wait_finished(job, 10.0);
  EXPECT_LT(latency, 0.05 * timing_slack()) << "cancel took " << latency << " s";
  job.wait();
  EXPECT_TRUE(job.finished());
  EXPECT_TRUE(job.cancelled());
  EXPECT_EQ(job.status(), "Cancelled");
  EXPECT_TRUE(job.error().empty());
  (void)t0;
}

TEST(Job, DestroyingARunningJobCancelsAndJoinsIt) {
  auto job = std::make_unique<TestJob>([](TestJob& self) {
    while (!self.cancel_flag()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  job->start();
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const auto t0 = Clock::now();
  job.reset();  // would hang (or std::terminate on a joinable thread) without cancel and join
  EXPECT_LT(seconds_since(t0), 0.05 * timing_slack());
}

TEST(Job, AnExceptionInTheWorkBecomesAnErrorStatus) {
  TestJob job([](TestJob& self) {
    self.set_status("Working");
    throw std::runtime_error("out of photons");
  });
  job.start();
  job.wait();
  EXPECT_TRUE(job.finished());
  EXPECT_EQ(job.status(), "Failed");
  EXPECT_EQ(job.error(), "out of photons");
  EXPECT_TRUE(job.cancelled()) << "a failure stops the rest of the work";
  const std::vector<std::string> warnings = job.warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "Test failed: out of photons");
  const JobSnapshot snapshot = job.snapshot();
  EXPECT_EQ(snapshot.status, "Failed");
  EXPECT_EQ(snapshot.error, "out of photons");
  EXPECT_TRUE(snapshot.finished);

  // Not derived from std::exception either.
  TestJob other([](TestJob&) { throw 42; });
  other.start();
  other.wait();
  EXPECT_EQ(other.status(), "Failed");
  EXPECT_EQ(other.error(), "unknown error");
}

TEST(Job, ProgressNeverGoesBackWhileWorkIsCountedAndEndsAtOne) {
  constexpr size_t kUnits = 20000;
  std::atomic<bool> release{false};
  TestJob job(
      [&release](TestJob& self) {
        const PrepareControl control = self.prepare_control();
        self.set_preparing(true);
        control.report("Preparing", 0.25f);
        while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        control.report("Preparing more", 0.0f / 0.0f);  // a NaN is shown as no progress
        while (release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        self.set_preparing(false);
        self.set_status("Working");
        tbb::parallel_for(size_t{0}, kUnits, [&](size_t) {
          std::this_thread::sleep_for(std::chrono::microseconds(50));
          ++self.work_done();
        });
      },
      kUnits);
  EXPECT_EQ(job.progress(), 0.0f) << "before start";
  job.start();
  while (job.status() != "Preparing") std::this_thread::sleep_for(std::chrono::milliseconds(1));
  JobSnapshot s = job.snapshot();
  EXPECT_TRUE(s.preparing);
  EXPECT_EQ(s.progress, 0.25f);
  release = true;
  while (job.status() != "Preparing more")
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(job.progress(), 0.0f);
  release = false;

  float last = -1.0f;
  size_t samples = 0, decreases = 0;
  while (!job.finished()) {
    s = job.snapshot();
    if (!s.preparing && s.status == "Working") {
      ASSERT_GE(s.progress, 0.0f);
      ASSERT_LE(s.progress, 1.0f);
      if (s.progress < last) ++decreases;
      last = s.progress;
      ++samples;
    }
  }
  job.wait();
  EXPECT_GT(samples, 10u);
  EXPECT_EQ(decreases, 0u);
  EXPECT_EQ(job.progress(), 1.0f);
  EXPECT_EQ(job.status(), "Done");
}

RenderSettings small_settings(IntegratorType type) {
  RenderSettings s;
  s.full_width = s.x1 = 16;
  s.full_height = s.y1 = 16;
  s.samples = 2;
  s.threads = 2;
  s.integrator = type;
  s.photons = 2000;
  s.caustic_photons = 0;
  s.final_gather_rays = 2;
  s.radiosity_rays = 20000;
  return s;
}

// The capability the factory states is what the integrator does: a type that can bake returns
// view-independent radiance for a diffuse point, one that cannot returns none.
TEST(IntegratorCapabilities, BakeAgreesWithTheIntegrator) {
  const Scene scene = make_cornell_box();
  for (IntegratorType type :
       {IntegratorType::kRayTrace, IntegratorType::kPhotonMap, IntegratorType::kRadiosity}) {
    const IntegratorCapabilities caps = integrator_capabilities(type);
    SCOPED_TRACE(caps.name);
    const RenderSettings settings = small_settings(type);
    std::vector<std::string> warnings;
    const SceneResources resources(scene, settings, &warnings);
    std::unique_ptr<Integrator> integrator = make_integrator(type);
    integrator->prepare(resources.context(), PrepareControl{});
    size_t baked = 0, points = 0;
    for (uint32_t instance = 0; instance < scene.instances.size(); ++instance) {
      Hit hit;
      if (!resources.accel().surface_hit(instance, 0, 0.25f, 0.25f, &hit)) continue;
      const SurfaceInteraction si = resources.accel().interaction(hit);
      Sampler sampler(1, instance, 0, 1);
      Vec3 radiance;
      ++points;
      baked += integrator->baked_radiance(resources.context(), hit, si, sampler, &radiance);
    }
    ASSERT_GT(points, 0u);
    if (caps.bake) {
      EXPECT_GT(baked, 0u) << "said to bake, baked nothing";
      EXPECT_STREQ(caps.no_bake_reason, "");
    } else {
      EXPECT_EQ(baked, 0u) << "said not to bake, baked";
      EXPECT_STRNE(caps.no_bake_reason, "");
      // A bake session reports the factory's reason as its error.
      BakeSession session(std::make_shared<Scene>(scene), settings, BakeOptions{},
                          {BakePoint{0, 0, 0.25f, 0.25f}});
      session.start();
      session.wait();
      EXPECT_EQ(session.result().error, caps.no_bake_reason);
    }
  }
}

// stop_early: Esc during the stated stage ends that stage at once, and the render goes on.
TEST(IntegratorCapabilities, StopEarlyEndsThePreparationInItsStage) {
  for (IntegratorType type : {IntegratorType::kPhotonMap, IntegratorType::kRadiosity}) {
    const IntegratorCapabilities caps = integrator_capabilities(type);
    SCOPED_TRACE(caps.name);
    ASSERT_TRUE(caps.stop_early);
    RenderSettings settings = small_settings(type);
    settings.photons = 100000000;         // minutes of tracing
    settings.radiosity_rays = 400000000;  // minutes of shooting
    settings.radiosity_threshold = 1e-4f;
    RenderSession session(std::make_shared<Scene>(make_cornell_box()), settings);
    session.start();
    const auto t0 = Clock::now();
    const std::string prefix = caps.stop_early_status;
    // The solver's own stages (past meshing) for the whole-preparation case.
    const std::string stage = prefix.empty() ? "Radiosity: iteration" : prefix;
    while (session.status().rfind(stage, 0) != 0 && seconds_since(t0) < 120.0 &&
           !session.finished())
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_TRUE(session.preparing()) << session.status();
    session.stop_preparation();
    // The stage ends at once (what follows it, e.g. building the maps of the photons traced
    // so far, still runs); without the stop it would run for minutes.
    const auto stopped = Clock::now();
    while (session.preparing() && session.status().rfind(stage, 0) == 0 &&
           seconds_since(stopped) < 30.0)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_LT(seconds_since(stopped), 1.0 * timing_slack()) << session.status();
    session.wait();
    EXPECT_EQ(session.status(), "Done") << "a stopped preparation still renders";
  }
}

}  // namespace
}  // namespace job_test
}  // namespace photon

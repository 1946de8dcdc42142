#include "photon/integrators/vcm/vcm_light_paths.h"

#include <gtest/gtest.h>

#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace vcm_light_paths_test {
namespace {

struct LightPathFixture {
  LightPathFixture()
      : scene(make_cornell_box()),
        resources(scene, settings, nullptr),
        frame(make_frame(resources.context())),
        lights(resources.context(), frame, nullptr),
        camera(film_frame(scene), FilmOptions{}) {}
  static PhotonFrame make_frame(const RenderContext& context) {
    const PhotonSources sources(context);
    return PhotonFrame{sources.scene_center(), sources.scene_radius()};
  }
  static FilmFrame film_frame(const Scene& scene) {
    FilmFrame f;
    f.camera = scene.camera;
    f.full_width = f.full_height = f.x1 = f.y1 = 32;
    return f;
  }
  Scene scene;
  RenderSettings settings;
  SceneResources resources;
  PhotonFrame frame;
  VcmLights lights;
  VcmCamera camera;
};

TEST(VcmLightPaths, PeakBytesGrowWithPathsVerticesAndSplats) {
  const double one = vcm_light_pass_peak_bytes(1000, 3.0, 1.0);
  EXPECT_DOUBLE_EQ(vcm_light_pass_peak_bytes(2000, 3.0, 1.0), 2.0 * one);
  EXPECT_GT(vcm_light_pass_peak_bytes(1000, 4.0, 1.0), one);
  EXPECT_GT(vcm_light_pass_peak_bytes(1000, 3.0, 2.0), one);
  // At least the vertices themselves, held twice while the chunks are joined.
  EXPECT_GE(one, 2.0 * 1000 * 3.0 * sizeof(VcmLightVertex));
}

TEST(VcmLightPaths, ARequestThatFitsIsTracedWithoutAPilot) {
  LightPathFixture f;
  const VcmMis mis = VcmMis::make(VcmMode::kVcm, 0.01f, 5000, 64);
  const VcmLightPathPlan plan =
      plan_vcm_light_paths(f.resources.context(), f.lights, f.camera, mis, 5000, 1e12);
  EXPECT_EQ(plan.light_paths, 5000u);
  EXPECT_EQ(plan.requested_bytes, 0.0);
  // Unknown memory: the request.
  EXPECT_EQ(
      plan_vcm_light_paths(f.resources.context(), f.lights, f.camera, mis, 5000, 0.0).light_paths,
      5000u);
}

// The UI's maximum (1e8 subpaths per iteration) went past 8 GB with no estimate.
TEST(VcmLightPaths, TheUisMaximumIsScaledDownToTheBudget) {
  LightPathFixture f;
  const uint64_t requested = 100000000;
  const double budget = 256e6;
  const VcmMis mis = VcmMis::make(VcmMode::kVcm, 0.01f, requested, 64);
  const VcmLightPathPlan plan =
      plan_vcm_light_paths(f.resources.context(), f.lights, f.camera, mis, requested, budget);
  EXPECT_GT(plan.requested_bytes, budget);
  ASSERT_LT(plan.light_paths, requested);
  ASSERT_GT(plan.light_paths, 0u);
  // The planned subpaths, traced, fit the budget by the same estimate from what they stored.
  VcmMis traced_mis = mis;
  traced_mis.light_paths = plan.light_paths;
  const std::atomic<bool> no_cancel{false};
  const VcmLightPass pass =
      trace_vcm_light_paths(f.resources.context(), f.lights, f.camera, traced_mis, 0, no_cancel);
  const double n = static_cast<double>(plan.light_paths);
  const double traced =
      vcm_light_pass_peak_bytes(n, pass.vertices.size() / n, pass.splats.size() / n);
  EXPECT_LT(traced, 1.05 * budget);
  EXPECT_GT(traced, 0.8 * budget);
  // A budget smaller than one subpath still traces one.
  EXPECT_EQ(plan_vcm_light_paths(f.resources.context(), f.lights, f.camera, mis, requested, 1.0)
                .light_paths,
            1u);
}

}  // namespace
}  // namespace vcm_light_paths_test
}  // namespace photon

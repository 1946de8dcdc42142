#include "photon/integrators/merge_radius.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "photon/integrators/photon_map/photon_sources.h"
#include "photon/integrators/vcm/vcm_integrator.h"
#include "photon/session/render_session.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace merge_radius_test {
namespace {

TEST(MergeRadius, RangeRunsFromATenthOfAPixelToAQuarterOfTheScene) {
  const RadiusRange r = meaningful_radius_range(0.01f, 2.0f, 0.02f);
  EXPECT_FLOAT_EQ(r.min, 0.001f);
  EXPECT_FLOAT_EQ(r.max, 0.5f);
}

TEST(MergeRadius, TheAutomaticRadiusIsAlwaysInsideTheRange) {
  // A tiny frame of a small scene: two pixels' footprint is wider than a quarter of the scene.
  const RadiusRange wide = meaningful_radius_range(0.4f, 1.0f, 0.8f);
  EXPECT_FLOAT_EQ(wide.max, 0.8f);
  // No surface seen (footprint 0): the automatic fallback still fits.
  const RadiusRange blind = meaningful_radius_range(0.0f, 1.0f, 0.01f);
  EXPECT_LE(blind.min, 0.01f);
  EXPECT_GE(blind.max, 0.01f);
}

TEST(MergeRadius, ClampingSaysWhichSettingAndWhatWasUsed) {
  const RadiusRange r = meaningful_radius_range(0.01f, 2.0f, 0.02f);
  std::string warning;
  EXPECT_FLOAT_EQ(clamp_radius("sppm_initial_radius", 0.1f, r, &warning), 0.1f);
  EXPECT_TRUE(warning.empty());
  EXPECT_FLOAT_EQ(clamp_radius("sppm_initial_radius", 1e-12f, r, &warning), 0.001f);
  EXPECT_NE(warning.find("sppm_initial_radius = 1e-12"), std::string::npos) << warning;
  EXPECT_NE(warning.find("tenth of a pixel"), std::string::npos) << warning;
  warning.clear();
  EXPECT_FLOAT_EQ(clamp_radius("vcm_initial_radius", 1e9f, r, &warning), 0.5f);
  EXPECT_NE(warning.find("vcm_initial_radius = 1e+09"), std::string::npos) << warning;
  EXPECT_NE(warning.find("quarter of the scene"), std::string::npos) << warning;
}

TEST(MergeRadius, PixelFootprintHalvesWhenTheResolutionDoubles) {
  const Scene scene = make_cornell_box();
  RenderSettings settings;
  SceneResources resources(scene, settings, nullptr);
  FilmFrame frame;
  frame.camera = scene.camera;
  frame.full_width = frame.full_height = frame.x1 = frame.y1 = 64;
  const float coarse = median_pixel_footprint(resources.context(), frame);
  frame.full_width = frame.full_height = frame.x1 = frame.y1 = 128;
  const float fine = median_pixel_footprint(resources.context(), frame);
  ASSERT_GT(fine, 0.0f);
  EXPECT_NEAR(coarse / fine, 2.0, 0.1);
}

struct Rendered {
  double mean = 0.0;
  std::vector<std::string> warnings;
  double seconds = 0.0;
};

Rendered render(const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  session.wait();
  Rendered r;
  const std::vector<float> rgba = session.image();
  for (size_t i = 0; i < rgba.size(); i += 4) r.mean += (rgba[i] + rgba[i + 1] + rgba[i + 2]) / 3.0;
  r.mean /= static_cast<double>(rgba.size() / 4);
  r.warnings = session.warnings();
  return r;
}

bool warned_about(const Rendered& r, const std::string& setting) {
  return std::any_of(r.warnings.begin(), r.warnings.end(),
                     [&](const std::string& w) { return w.find(setting) != std::string::npos; });
}

RenderSettings iterative(IntegratorType type, float radius) {
  RenderSettings s;
  s.full_width = s.full_height = s.x1 = s.y1 = 48;
  s.seed = 3;
  s.integrator = type;
  s.sppm_iterations = s.vcm_iterations = 8;
  s.sppm_photons_per_iteration = s.vcm_light_paths = 20000;
  s.sppm_initial_radius = s.vcm_initial_radius = radius;
  return s;
}

// A radius far below a pixel caught almost no photon: the Cornell box lost half its light.
TEST(MergeRadius, SppmWithAVanishingRadiusKeepsItsIndirectLightAndWarns) {
  const Rendered automatic = render(iterative(IntegratorType::kSppm, 0.0f));
  const Rendered tiny = render(iterative(IntegratorType::kSppm, 1e-12f));
  EXPECT_FALSE(warned_about(automatic, "sppm_initial_radius"));
  EXPECT_TRUE(warned_about(tiny, "sppm_initial_radius"));
  EXPECT_NEAR(tiny.mean / automatic.mean, 1.0, 0.1) << tiny.mean << " vs " << automatic.mean;
}

// A merging radius wider than the scene read every light vertex at every pixel.
TEST(MergeRadius, VcmWithARadiusWiderThanTheSceneIsClampedAndWarns) {
  // Fewer light paths than the SPPM case: even clamped, every merge reads most of them.
  RenderSettings s = iterative(IntegratorType::kVcm, 0.0f);
  s.vcm_light_paths = 5000;
  const Rendered automatic = render(s);
  s.vcm_initial_radius = 1e9f;
  const Rendered huge = render(s);
  EXPECT_FALSE(warned_about(automatic, "vcm_initial_radius"));
  EXPECT_TRUE(warned_about(huge, "vcm_initial_radius"));
  EXPECT_NEAR(huge.mean / automatic.mean, 1.0, 0.1) << huge.mean << " vs " << automatic.mean;
}

TEST(MergeRadius, VcmRadiusIsAtMostAQuarterOfTheScene) {
  const Scene scene = make_cornell_box();
  const RenderSettings s = iterative(IntegratorType::kVcm, 1e9f);
  SceneResources resources(scene, s, nullptr);
  VcmIntegrator vcm;
  vcm.prepare(resources.context(), PrepareControl{});
  FilmFrame frame;
  frame.camera = scene.camera;
  frame.full_width = frame.full_height = frame.x1 = frame.y1 = 48;
  Film film(frame, FilmOptions{});
  RenderControl control;
  control.end_pass = 1;
  vcm.render(resources.context(), film, control);
  const PhotonSources sources(resources.context());
  EXPECT_LE(vcm.radius(0), 0.25f * sources.scene_radius() * 1.0001f);
  EXPECT_GT(vcm.radius(0), 0.0f);
}

}  // namespace
}  // namespace merge_radius_test
}  // namespace photon

// Adaptive sampling in a final render (SamplingParams::adaptive_sampling): pixels stop once
// converged, the image estimates the same picture as every sample would, the result does not
// depend on threads or tiles, the data passes are all written, and the iterative integrators
// say they do not use it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "photon/film/pass_layout.h"
#include "photon/testing/session_output.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace adaptive_sampling_test {
namespace {

constexpr int kWidth = 32, kHeight = 24;

// With the Depth pass only, SessionOutput::data is the Depth of every pixel.
SessionOutput render(const RenderSettings& s) {
  return render_whole_session(std::make_shared<Scene>(make_cornell_box()), s);
}

RenderSettings settings(int samples, bool adaptive) {
  RenderSettings s;
  s.full_width = s.x1 = kWidth;
  s.full_height = s.y1 = kHeight;
  s.samples = samples;
  s.seed = 5;
  s.integrator = IntegratorType::kRayTrace;
  s.tile_size = 16;
  s.adaptive_sampling = adaptive;
  s.adaptive_threshold = 0.05f;
  s.data_passes.mask = kPassDepth;
  return s;
}

double mean(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); ++i)
    if (i % 4 != 3) sum += rgba[i];
  return sum / (rgba.size() / 4 * 3);
}

TEST(AdaptiveSampling, ConvergedPixelsStopAndTheImageStaysTheSame) {
  const int samples = 512;
  const SessionOutput adaptive = render(settings(samples, true));
  const SessionOutput full = render(settings(samples, false));
  const uint64_t pixels = kWidth * kHeight;
  EXPECT_EQ(full.camera_samples, pixels * samples);
  // Threshold 0.05: Cycles' automatic minimum is 40 samples, first judged after 48; far fewer
  // than all of them in the box's smooth walls.
  EXPECT_GE(adaptive.camera_samples, pixels * 48);
  EXPECT_LT(adaptive.camera_samples, pixels * samples / 2);
  std::printf("[ adaptive ] %.1f samples per pixel of %d, mean %.5f against %.5f\n",
              static_cast<double>(adaptive.camera_samples) / pixels, samples, mean(adaptive.image),
              mean(full.image));
  EXPECT_NEAR(mean(adaptive.image) / mean(full.image), 1.0, 0.01);
  // Per pixel within the noise the threshold allows (Cycles' measure, 5 x 0.05 relative to the
  // square root of the pixel's brightness), for all but a few pixels.
  int far = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const float a = adaptive.image[4 * p] + adaptive.image[4 * p + 1] + adaptive.image[4 * p + 2];
    const float b = full.image[4 * p] + full.image[4 * p + 1] + full.image[4 * p + 2];
    far += std::abs(a - b) > 0.25f * std::sqrt(std::max(b, 1e-3f)) + 1e-3f;
  }
  EXPECT_LE(far, static_cast<int>(pixels / 50)) << far;
  // Depth is written for every pixel, from the samples reached.
  EXPECT_EQ(std::count(adaptive.data.begin(), adaptive.data.end(), -9.0f), 0);
  for (const std::string& w : adaptive.warnings) ADD_FAILURE() << w;
}

TEST(AdaptiveSampling, SameImageForAnyThreadsAndTiles) {
  RenderSettings one = settings(256, true);
  one.threads = 1;
  one.tile_size = 8;
  RenderSettings two = settings(256, true);
  two.threads = 2;
  two.tile_size = 32;
  const SessionOutput a = render(one), b = render(two);
  EXPECT_EQ(a.camera_samples, b.camera_samples);
  EXPECT_EQ(a.image, b.image);
  EXPECT_EQ(a.data, b.data);
}

TEST(AdaptiveSampling, IterativeIntegratorsSayTheyDoNotUseIt) {
  RenderSettings s = settings(2, true);
  s.integrator = IntegratorType::kSppm;
  s.sppm_iterations = 2;
  s.sppm_photons_per_iteration = 2000;
  const SessionOutput out = render(s);
  const bool said = std::any_of(out.warnings.begin(), out.warnings.end(), [](const std::string& w) {
    return w.find("Noise Threshold is not used by") == 0;
  });
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace adaptive_sampling_test
}  // namespace photon

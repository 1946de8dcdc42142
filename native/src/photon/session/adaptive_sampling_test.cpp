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
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace adaptive_sampling_test {
namespace {

struct Output {
  std::vector<float> image;
  std::vector<float> depth;  // the Depth pass as the last tiles left it
  std::vector<std::string> warnings;
  uint64_t camera_samples = 0;
};

constexpr int kWidth = 32, kHeight = 24;

Output render(const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  Output out;
  out.depth.assign(static_cast<size_t>(kWidth) * kHeight, -9.0f);
  while (true) {
    const bool done = session.finished();
    for (const Tile& t : session.take_tiles(0.05)) {
      const PassImage* depth = t.pass("Depth");
      if (!depth) continue;
      for (int row = 0; row < t.height; ++row)
        for (int col = 0; col < t.width; ++col)
          out.depth[static_cast<size_t>(t.y + row) * kWidth + t.x + col] =
              depth->pixels[static_cast<size_t>(row) * t.width + col];
    }
    if (done) break;
  }
  session.wait();
  out.image = session.image();
  out.warnings = session.warnings();
  out.camera_samples = session.stats().camera_samples;
  return out;
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
  const Output adaptive = render(settings(samples, true));
  const Output full = render(settings(samples, false));
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
  EXPECT_EQ(std::count(adaptive.depth.begin(), adaptive.depth.end(), -9.0f), 0);
  for (const std::string& w : adaptive.warnings) ADD_FAILURE() << w;
}

TEST(AdaptiveSampling, SameImageForAnyThreadsAndTiles) {
  RenderSettings one = settings(256, true);
  one.threads = 1;
  one.tile_size = 8;
  RenderSettings two = settings(256, true);
  two.threads = 2;
  two.tile_size = 32;
  const Output a = render(one), b = render(two);
  EXPECT_EQ(a.camera_samples, b.camera_samples);
  EXPECT_EQ(a.image, b.image);
  EXPECT_EQ(a.depth, b.depth);
}

TEST(AdaptiveSampling, IterativeIntegratorsSayTheyDoNotUseIt) {
  RenderSettings s = settings(2, true);
  s.integrator = IntegratorType::kSppm;
  s.sppm_iterations = 2;
  s.sppm_photons_per_iteration = 2000;
  const Output out = render(s);
  const bool said = std::any_of(out.warnings.begin(), out.warnings.end(), [](const std::string& w) {
    return w.find("Noise Threshold is not used by") == 0;
  });
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace adaptive_sampling_test
}  // namespace photon

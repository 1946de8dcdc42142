// Time Limit (SamplingParams::time_limit): a render stops adding samples when its budget is spent,
// every pixel with the same samples; its image estimates the same picture, and its data passes
// are exactly those of a render asked for that many samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "photon/film/pass_layout.h"
#include "photon/testing/session_output.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace time_limit_test {
namespace {

SessionOutput render(const RenderSettings& s) {
  return render_whole_session(std::make_shared<Scene>(make_cornell_box()), s);
}

RenderSettings settings(int samples, float time_limit) {
  RenderSettings s;
  s.full_width = s.x1 = 32;
  s.full_height = s.y1 = 24;
  s.samples = samples;
  s.seed = 3;
  s.integrator = IntegratorType::kRayTrace;
  s.tile_size = 16;
  s.time_limit = time_limit;
  s.data_passes.mask = kPassDepth | kPassNormal | kPassDiffuseColor;
  return s;
}

TEST(TimeLimit, StopsAtWholePassesWithTheImageOfThatManySamples) {
  const int asked = 1 << 20;
  const SessionOutput limited = render(settings(asked, 0.3f));
  const uint64_t pixels = 32 * 24;
  ASSERT_GT(limited.camera_samples, 0u);
  ASSERT_EQ(limited.camera_samples % pixels, 0u);  // every pixel the same samples
  const int reached = static_cast<int>(limited.camera_samples / pixels);
  ASSERT_LT(reached, asked);
  const auto said = std::find_if(limited.warnings.begin(), limited.warnings.end(),
                                 [](const std::string& w) { return w.find("Time Limit") == 0; });
  ASSERT_NE(said, limited.warnings.end());
  EXPECT_NE(said->find("after " + std::to_string(reached) + " of"), std::string::npos) << *said;

  const SessionOutput same = render(settings(reached, 0.0f));
  EXPECT_EQ(limited.data, same.data);
  // The rounds' samples are other R2 points' pairings than one call's, so the image is another
  // estimate of the same picture (both have hundreds of samples per pixel).
  ASSERT_GE(reached, 64);
  double a = 0.0, b = 0.0;
  for (size_t i = 0; i < same.image.size(); ++i)
    if (i % 4 != 3) a += limited.image[i], b += same.image[i];
  EXPECT_NEAR(a / b, 1.0, 0.02);
  EXPECT_EQ(std::count(limited.data.begin(), limited.data.end(), -9.0f), 0);  // all written
}

// A budget the render does not need: all samples and no message.
TEST(TimeLimit, AnAmpleBudgetRendersEverySample) {
  const SessionOutput limited = render(settings(16, 600.0f));
  const SessionOutput plain = render(settings(16, 0.0f));
  EXPECT_EQ(limited.camera_samples, 32u * 24u * 16u);
  EXPECT_EQ(limited.data, plain.data);
  for (const std::string& w : limited.warnings) EXPECT_EQ(w.find("Time Limit"), std::string::npos);
}

}  // namespace
}  // namespace time_limit_test
}  // namespace photon

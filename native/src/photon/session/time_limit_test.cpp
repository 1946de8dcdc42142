// Time Limit (SamplingParams::time_limit): a render stops adding samples when its budget is spent,
// every pixel with the same samples; its image estimates the same picture, and its data passes
// are exactly those of a render asked for that many samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "photon/film/pass_layout.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace time_limit_test {
namespace {

struct Output {
  std::vector<float> image;
  std::vector<float> data;  // every data pass of every pixel, as the last tiles left them
  std::vector<std::string> warnings;
  uint64_t camera_samples = 0;
};

Output render(const RenderSettings& s) {
  RenderSession session(std::make_shared<Scene>(make_cornell_box()), s);
  session.start();
  Output out;
  const int floats = data_pass_pixel_floats(s.data_passes);
  out.data.assign(static_cast<size_t>(s.full_width) * s.full_height * floats, -9.0f);
  while (true) {
    const bool done = session.finished();
    // Later tiles (a later round, or the whole film after the data passes) replace earlier ones.
    for (const Tile& t : session.take_tiles(0.05))
      for (const DataPassSlot& slot : data_pass_slots(s.data_passes)) {
        const PassImage* pass = t.pass(slot.name);
        if (!pass) continue;
        for (int row = 0; row < t.height; ++row)
          for (int col = 0; col < t.width; ++col)
            std::copy_n(
                &pass->pixels[(static_cast<size_t>(row) * t.width + col) * slot.channels],
                slot.channels,
                &out.data[(static_cast<size_t>(t.y + row) * s.full_width + t.x + col) * floats +
                          slot.offset]);
      }
    if (done) break;
  }
  session.wait();
  out.image = session.image();
  out.warnings = session.warnings();
  out.camera_samples = session.stats().camera_samples;
  return out;
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
  const Output limited = render(settings(asked, 0.3f));
  const uint64_t pixels = 32 * 24;
  ASSERT_GT(limited.camera_samples, 0u);
  ASSERT_EQ(limited.camera_samples % pixels, 0u);  // every pixel the same samples
  const int reached = static_cast<int>(limited.camera_samples / pixels);
  ASSERT_LT(reached, asked);
  const auto said = std::find_if(limited.warnings.begin(), limited.warnings.end(),
                                 [](const std::string& w) { return w.find("Time Limit") == 0; });
  ASSERT_NE(said, limited.warnings.end());
  EXPECT_NE(said->find("after " + std::to_string(reached) + " of"), std::string::npos) << *said;

  const Output same = render(settings(reached, 0.0f));
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
  const Output limited = render(settings(16, 600.0f));
  const Output plain = render(settings(16, 0.0f));
  EXPECT_EQ(limited.camera_samples, 32u * 24u * 16u);
  EXPECT_EQ(limited.data, plain.data);
  for (const std::string& w : limited.warnings) EXPECT_EQ(w.find("Time Limit"), std::string::npos);
}

}  // namespace
}  // namespace time_limit_test
}  // namespace photon

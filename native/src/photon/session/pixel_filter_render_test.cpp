// The film settings in a whole render: a Blackman-Harris image is the same for any thread count
// and tile size (each pixel's samples and filter offsets depend on the pixel only), differs from
// the box image, and film exposure scales colour exactly while alpha stays.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace pixel_filter_render_test {
namespace {

std::vector<float> render_image(const std::shared_ptr<const Scene>& scene,
                                const RenderSettings& settings) {
  RenderSession session(scene, settings);
  session.start();
  session.wait();
  EXPECT_TRUE(session.finished());
  return session.image();
}

RenderSettings film_settings(int threads, int tile_size) {
  RenderSettings s;
  s.full_width = s.x1 = 40;
  s.full_height = s.y1 = 32;
  s.integrator = IntegratorType::kRayTrace;
  s.samples = 4;
  s.seed = 5;
  s.threads = threads;
  s.tile_size = tile_size;
  s.filter_type = PixelFilterType::kBlackmanHarris;
  s.filter_width = 1.5f;
  return s;
}

TEST(PixelFilterRender, SameImageForAnyThreadsOrTiles) {
  const auto scene = std::make_shared<Scene>(make_cornell_box());
  const std::vector<float> a = render_image(scene, film_settings(1, 8));
  EXPECT_TRUE(a == render_image(scene, film_settings(2, 32)));
  EXPECT_TRUE(a == render_image(scene, film_settings(2, 5)));  // tiles that do not divide it
  RenderSettings box = film_settings(1, 8);
  box.filter_type = PixelFilterType::kBox;
  EXPECT_FALSE(a == render_image(scene, box));  // the filter moves the samples
}

TEST(PixelFilterRender, ExposureScalesColourOnly) {
  const auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings s = film_settings(2, 16);
  const std::vector<float> once = render_image(scene, s);
  s.exposure = 2.0f;
  const std::vector<float> twice = render_image(scene, s);
  ASSERT_EQ(once.size(), twice.size());
  float brightest = 0.0f;
  for (size_t i = 0; i < once.size(); ++i) {
    if (i % 4 == 3) {
      EXPECT_EQ(twice[i], once[i]) << "alpha at " << i / 4;
    } else {
      EXPECT_EQ(twice[i], 2.0f * once[i]) << "channel " << i % 4 << " at " << i / 4;
      brightest = std::max(brightest, once[i]);
    }
  }
  EXPECT_GT(brightest, 0.1f);
}

}  // namespace
}  // namespace pixel_filter_render_test
}  // namespace photon

// A render border does not change the iterative integrators' pixels: a band of an SPPM or a
// VCM render (in each VCM mode) equals the same rows of the full render bit for bit, so a
// render farm's split frame stitches into the full image. Automatic radii are the ones that
// could depend on the region: SPPM's fallback radius for pixels that see nothing and VCM's
// initial merging radius are medians over the whole frame.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace iterative_border_test {
namespace {

constexpr int kWidth = 36, kHeight = 30;

// The Cornell box seen from farther back through a wide lens: the frame's edges see the empty
// world (SPPM's fallback radius) and the depth seen varies from band to band (VCM's radius).
std::shared_ptr<const Scene> far_cornell_box() {
  Scene scene = make_cornell_box();
  scene.camera = make_look_at_camera(Vec3(0.0f, -4.5f, 1.0f), Vec3(0.0f, 0.0f, 0.6f), 1.1f,
                                     static_cast<float>(kWidth) / kHeight);
  return std::make_shared<const Scene>(std::move(scene));
}

RenderSettings iterative_settings(IntegratorType integrator, VcmMode mode) {
  RenderSettings s;
  s.integrator = integrator;
  s.vcm_mode = mode;
  s.full_width = kWidth, s.full_height = kHeight;
  s.x0 = 0, s.y0 = 0, s.x1 = kWidth, s.y1 = kHeight;
  s.sppm_iterations = 3;
  s.vcm_iterations = 3;
  s.sppm_photons_per_iteration = 4000;
  s.vcm_light_paths = 4000;
  s.seed = 11;
  s.threads = 2;
  return s;
}

std::vector<float> render(const std::shared_ptr<const Scene>& scene, const RenderSettings& s) {
  RenderSession session(scene, s);
  session.start();
  session.wait();
  EXPECT_EQ(session.status(), "Done");
  EXPECT_EQ(session.stats().iterations.iterations, 3);
  return session.image();
}

void expect_band_matches_full(IntegratorType integrator, VcmMode mode, const char* what) {
  SCOPED_TRACE(what);
  const auto scene = far_cornell_box();
  const RenderSettings full = iterative_settings(integrator, mode);
  const std::vector<float> whole = render(scene, full);
  // Top, middle and bottom bands, and a border off the frame's centre.
  for (const auto& [x0, y0, x1, y1] :
       {std::array<int, 4>{0, 0, kWidth, 8}, std::array<int, 4>{0, 8, kWidth, 19},
        std::array<int, 4>{0, 19, kWidth, kHeight}, std::array<int, 4>{20, 3, 33, 12}}) {
    RenderSettings border = full;
    border.x0 = x0, border.y0 = y0, border.x1 = x1, border.y1 = y1;
    const std::vector<float> part = render(scene, border);
    const int w = x1 - x0;
    ASSERT_EQ(part.size(), static_cast<size_t>(w) * (y1 - y0) * 4);
    int different = 0;
    for (int y = y0; y < y1; ++y)
      different += std::memcmp(&part[static_cast<size_t>(y - y0) * w * 4],
                               &whole[(static_cast<size_t>(y) * kWidth + x0) * 4],
                               static_cast<size_t>(w) * 4 * sizeof(float)) != 0;
    EXPECT_EQ(different, 0) << "rows of the border " << x0 << "," << y0 << " - " << x1 << "," << y1
                            << " differ from the full render";
  }
}

TEST(IterativeBorder, SppmBandEqualsTheFullRender) {
  expect_band_matches_full(IntegratorType::kSppm, VcmMode::kVcm, "SPPM");
}

TEST(IterativeBorder, VcmBandEqualsTheFullRenderInEveryMode) {
  expect_band_matches_full(IntegratorType::kVcm, VcmMode::kVcm, "VCM");
  expect_band_matches_full(IntegratorType::kVcm, VcmMode::kBpt, "BPT");
  expect_band_matches_full(IntegratorType::kVcm, VcmMode::kPpm, "PPM");
}

}  // namespace
}  // namespace iterative_border_test
}  // namespace photon

// What a render shows before it is done: the quick preview (a whole-frame direct-light image
// before the integrator's preparation) and, for a render cancelled inside a tile, the rows of
// that tile it had finished.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "photon/session/quick_preview.h"
#include "photon/session/render_session.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace render_early_image_test {
namespace {

RenderSettings settings_for(int size, int spp, IntegratorType integrator) {
  RenderSettings s;
  s.full_width = s.x1 = size;
  s.full_height = s.y1 = size;
  s.samples = spp;
  s.seed = 3;
  s.threads = 2;
  s.integrator = integrator;
  s.photons = 20000;
  s.caustic_photons = 2000;
  s.final_gather_rays = 8;
  return s;
}

double mean_rgb(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
  return sum / (3.0 * static_cast<double>(rgba.size() / 4));
}

TEST(QuickPreview, BlockSizeKeepsTheSampleBudget) {
  EXPECT_EQ(preview_block_size(64, 64), 1);
  EXPECT_EQ(preview_block_size(181, 181), 1);
  EXPECT_EQ(preview_block_size(256, 256), 2);
  EXPECT_EQ(preview_block_size(1920, 1080), 8);
  for (int w : {1, 300, 1920, 4096, 65536}) {
    const int b = preview_block_size(w, w / 2 + 1);
    const double samples = std::ceil(static_cast<double>(w) / b) * std::ceil((w / 2 + 1.0) / b);
    EXPECT_LE(samples * kPreviewSamples, 1.2 * kPreviewSampleBudget + 4) << w;
  }
}

// The preview arrives while the photon maps are still being built, covers the whole frame and
// sees the Cornell box's direct light; the render it came from is not changed by it.
TEST(QuickPreview, ArrivesBeforeThePreparationEndsAndLeavesTheRenderUnchanged) {
  const auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings s = settings_for(128, 4, IntegratorType::kPhotonMap);
  s.tile_size = 32;
  RenderSession with(scene, s);
  with.set_quick_preview(true);
  with.start();
  std::vector<float> preview;
  bool got_preview_while_preparing = false;
  while (!with.finished()) {
    const bool preparing_before = with.preparing() || with.status() == "Quick preview";
    if (with.take_preview(&preview)) {
      got_preview_while_preparing = preparing_before || with.preparing();
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(preview.size(), size_t{128} * 128 * 4);
  EXPECT_TRUE(got_preview_while_preparing) << "status " << with.status();
  std::vector<float> again;
  EXPECT_FALSE(with.take_preview(&again)) << "the preview is handed out once";
  with.wait();
  // It is the frame's direct light (and specular paths): its mean is that of a converged
  // ray-traced render of the same frame.
  RenderSettings direct = s;
  direct.integrator = IntegratorType::kRayTrace;
  direct.samples = 64;
  RenderSession converged(scene, direct);
  converged.start();
  converged.wait();
  EXPECT_NEAR(mean_rgb(preview), mean_rgb(converged.image()), 0.05 * mean_rgb(converged.image()));

  RenderSession without(scene, s);
  without.start();
  without.wait();
  EXPECT_FALSE(without.take_preview(&again));
  EXPECT_EQ(with.image(), without.image());
}

// A cancel inside a tile keeps the tile's finished rows, bit-identical to the same rows of a
// render that was not cancelled, and the assembled image keeps them too.
TEST(RenderSessionCancel, KeepsTheFinishedRowsOfATile) {
  const auto scene = std::make_shared<Scene>(make_cornell_box());
  RenderSettings s = settings_for(48, 256, IntegratorType::kRayTrace);
  s.tile_size = 64;  // one tile: the whole frame
  s.threads = 1;
  RenderSession full(scene, s);
  full.start();
  full.wait();
  const std::vector<float> reference = full.image();

  RenderSession session(scene, s);
  session.start();
  std::vector<Tile> tiles;
  const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (tiles.empty() && std::chrono::steady_clock::now() < limit) {
    // Cancel once the render has got some way into the tile.
    if (session.status() == "Rendering") {
      std::this_thread::sleep_for(std::chrono::milliseconds(150));
      session.cancel();
    }
    for (Tile& t : session.take_tiles(0.01)) tiles.push_back(std::move(t));
    if (session.finished()) break;
  }
  session.wait();
  for (Tile& t : session.take_tiles(0.0)) tiles.push_back(std::move(t));
  ASSERT_EQ(tiles.size(), 1u) << "the render did not reach a partial tile";
  const Tile& tile = tiles[0];
  EXPECT_GT(tile.height, 0);
  EXPECT_LT(tile.height, 48) << "the tile finished before the cancel: make it slower";
  ASSERT_EQ(tile.rgba.size(), static_cast<size_t>(tile.width) * tile.height * 4);
  const std::vector<float> kept(reference.begin(), reference.begin() + tile.rgba.size());
  EXPECT_EQ(tile.rgba, kept);
  const std::vector<float> image = session.image();
  EXPECT_TRUE(std::equal(kept.begin(), kept.end(), image.begin()));
}

}  // namespace
}  // namespace render_early_image_test
}  // namespace photon

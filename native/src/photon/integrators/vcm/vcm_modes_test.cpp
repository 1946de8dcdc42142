// VCM's modes estimate one image: with merging off (BPT) the connections' weights must make up
// merging's share, and with connections off (PPM) merging must make up theirs. Compared tile by
// tile with a tolerance from the noise each mode measures for itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "photon/testing/progressive_checkpoints.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace vcm_modes_test {
namespace {

constexpr int kSize = 32, kTile = 8, kTiles = (kSize / kTile) * (kSize / kTile);
constexpr int kReplicas = 16;

// Per-tile means of one mode over kReplicas independent one-iteration renders (distinct seeds),
// and their standard errors; the last entry is the whole image.
struct TileStats {
  std::vector<double> mean, standard_error;
};

TileStats tile_stats(const Scene& scene, VcmMode mode, uint64_t first_seed) {
  std::vector<std::vector<double>> replicas;
  for (int k = 0; k < kReplicas; ++k) {
    RenderSettings s;
    s.full_width = s.full_height = kSize;
    s.seed = first_seed + k;
    s.integrator = IntegratorType::kVcm;
    s.vcm_mode = mode;
    s.vcm_light_paths = 20000;
    // A merging radius of about a fifth of a pixel: the blur and the light that merging moves
    // across edges (the tall block's lit top into its front) stay well below the tiles' noise;
    // at the automatic radius (two pixels) merging brightens the tile under that edge by 7-12%
    // after 16 iterations.
    s.vcm_initial_radius = 0.02f;
    const std::vector<Checkpoint> c = render_checkpoints(scene, s, {1});
    std::vector<double> t(kTiles + 1, 0.0);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const double v = c[0].rgba[(static_cast<size_t>(y) * kSize + x) * 4 + ch];
          t[(y / kTile) * (kSize / kTile) + x / kTile] += v / (3.0 * kTile * kTile);
          t[kTiles] += v / (3.0 * kSize * kSize);
        }
    replicas.push_back(t);
  }
  TileStats out;
  for (int i = 0; i <= kTiles; ++i) {
    double mean = 0.0, var = 0.0;
    for (const auto& t : replicas) mean += t[i] / kReplicas;
    for (const auto& t : replicas) var += (t[i] - mean) * (t[i] - mean) / (kReplicas - 1);
    out.mean.push_back(mean);
    out.standard_error.push_back(std::sqrt(var / kReplicas));
  }
  return out;
}

const char* mode_name(VcmMode m) {
  return m == VcmMode::kVcm ? "VCM" : m == VcmMode::kBpt ? "BPT" : "PPM";
}

TEST(VcmModes, AgreeTileByTileWithinTheirMeasuredNoiseOnTheCornellBox) {
  // Diffuse surfaces and an area light: every mode finds every path. Each mode's replicas use
  // seeds of their own, so the modes' errors are independent.
  const Scene scene = make_cornell_box();
  const VcmMode modes[] = {VcmMode::kVcm, VcmMode::kBpt, VcmMode::kPpm};
  std::vector<TileStats> stats;
  for (int m = 0; m < 3; ++m) stats.push_back(tile_stats(scene, modes[m], 1000 * (m + 1)));
  for (auto [a, b] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    double chi2 = 0.0;
    for (int i = 0; i <= kTiles; ++i) {
      const double se = std::hypot(stats[a].standard_error[i], stats[b].standard_error[i]);
      ASSERT_GT(se, 0.0);
      const double z = (stats[a].mean[i] - stats[b].mean[i]) / se;
      if (i < kTiles) chi2 += z * z;
      // With 15 degrees of freedom, |t| > 4.5 has probability 4e-4 per comparison.
      EXPECT_LT(std::fabs(z), 4.5)
          << mode_name(modes[a]) << " vs " << mode_name(modes[b])
          << (i < kTiles ? " tile " + std::to_string(i) : " image") << ": " << stats[a].mean[i]
          << " vs " << stats[b].mean[i] << " +- " << se;
    }
    // The sum of 16 squared z-scores is about chi-square with 16 degrees of freedom (a little
    // wider, the errors being estimated): 0.999 of it lies below 39.3.
    EXPECT_LT(chi2, 45.0) << mode_name(modes[a]) << " vs " << mode_name(modes[b]);
    std::printf(
        "%s vs %s: image %.4f vs %.4f (+- %.4f), tiles' chi-square %.1f over %d\n",
        mode_name(modes[a]), mode_name(modes[b]), stats[a].mean[kTiles], stats[b].mean[kTiles],
        std::hypot(stats[a].standard_error[kTiles], stats[b].standard_error[kTiles]), chi2, kTiles);
  }
}

}  // namespace
}  // namespace vcm_modes_test
}  // namespace photon

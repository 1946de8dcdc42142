// SPPM and VCM on the specular-diffuse-specular scenes (testing/sds_scenes.h) against their
// stored references (test_scenes/sds/NAME.exr, 96 x 96, made by
// test_scenes/sds/make_references.py and checked there against VCM, photon mapping and Cycles):
// the error falls from 4 to 16 to 64 iterations and the image mean after 64 is near the
// reference's.
//
// The renders are 48 x 48: with the box filter of width 1 each pixel estimates the mean of a
// 2 x 2 block of the reference, so the reference is compared block by block. The error is the
// relative mean absolute error; the relative RMSE (printed too) is made by the few pixels that
// see the small light through glass now and then.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "photon/testing/node_references.h"
#include "photon/testing/progressive_checkpoints.h"
#include "photon/testing/sds_scenes.h"

namespace photon {
namespace sds_convergence_test {
namespace {

#ifndef PHOTON_SDS_REFS
#define PHOTON_SDS_REFS "test_scenes/sds"
#endif

struct SdsCase {
  const char* scene;
  IntegratorType integrator;
  // |mean / reference mean - 1| after 64 iterations must stay below this.
  double mean_tolerance;
  uint64_t photons = 50000;  // per iteration
};

std::string case_name(const ::testing::TestParamInfo<SdsCase>& info) {
  return std::string(info.param.scene) +
         (info.param.integrator == IntegratorType::kSppm ? "_sppm" : "_vcm");
}

class SdsConvergence : public ::testing::TestWithParam<SdsCase> {};

TEST_P(SdsConvergence, ErrorFallsAndTheMeanApproachesTheReference) {
  const SdsCase& c = GetParam();
  RgbImage stored;
  const std::string path = std::string(PHOTON_SDS_REFS) + "/" + c.scene + ".exr";
  ASSERT_TRUE(read_rgb_exr(path, &stored)) << "cannot read " << path;
  ASSERT_EQ(stored.width, 96);
  const Rgb reference = downsample(Rgb{stored.width, stored.height, stored.rgb}, 2);

  Scene scene;
  ASSERT_TRUE(make_sds_scene(c.scene, &scene));
  RenderSettings s;
  s.full_width = s.full_height = 48;
  s.seed = 11;
  s.integrator = c.integrator;
  s.sppm_photons_per_iteration = c.photons;
  s.vcm_light_paths = c.photons;
  const int counts[] = {4, 16, 64};
  const std::vector<Checkpoint> renders = render_checkpoints(scene, s, {4, 16, 64});
  ASSERT_EQ(renders.size(), 3u);
  double mae[3], rmse[3], mean[3];
  for (int k = 0; k < 3; ++k) {
    const Rgb image = rgb_of(renders[k].rgba, 48, 48);
    mae[k] = relative_mae(image, reference);
    rmse[k] = relative_rmse(image, reference);
    mean[k] = relative_mean_difference(image, reference);
  }
  std::printf(
      "%s after %d / %d / %d iterations: relative MAE %.4f / %.4f / %.4f, RMSE %.4f / "
      "%.4f / %.4f, mean %+.4f / %+.4f / %+.4f (%.1f s)\n",
      case_name({c, 0}).c_str(), counts[0], counts[1], counts[2], mae[0], mae[1], mae[2], rmse[0],
      rmse[1], rmse[2], mean[0], mean[1], mean[2], renders[2].seconds);
  // Noise alone would fall to (1/4)^(1/2) = 0.5 at each step, SPPM's radius bias to (1/4)^(1/3).
  EXPECT_LT(mae[1], 0.8 * mae[0]);
  EXPECT_LT(mae[2], 0.8 * mae[1]);
  EXPECT_LT(std::fabs(mean[2]), c.mean_tolerance);
}

// Measured (relative MAE after 4 / 16 / 64 iterations, mean after 64): glass_light (25k photons
// per iteration, its light bouncing long in the closed room) SPPM 0.183 / 0.134 / 0.041, +0.1%;
// VCM 0.182 / 0.106 / 0.052, -0.9%. mirror_caustic (50k) SPPM 0.363 / 0.200 / 0.138, +0.9%;
// VCM 0.243 / 0.144 / 0.088, -1.3%. pool (50k) SPPM 0.354 / 0.232 / 0.147, -0.7%; VCM 0.347 /
// 0.212 / 0.133, +0.6%. About 16 s in all, 11 of them glass_light's.
INSTANTIATE_TEST_SUITE_P(
    Scenes, SdsConvergence,
    ::testing::Values(SdsCase{"glass_light", IntegratorType::kSppm, 0.02, 25000},
                      SdsCase{"glass_light", IntegratorType::kVcm, 0.02, 25000},
                      SdsCase{"mirror_caustic", IntegratorType::kSppm, 0.02},
                      SdsCase{"mirror_caustic", IntegratorType::kVcm, 0.02},
                      SdsCase{"pool", IntegratorType::kSppm, 0.02},
                      SdsCase{"pool", IntegratorType::kVcm, 0.02}),
    case_name);

}  // namespace
}  // namespace sds_convergence_test
}  // namespace photon

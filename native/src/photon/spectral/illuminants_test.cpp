// Planck's law against Blender's Blackbody node, and Cauchy dispersion from an Abbe number.
#include "photon/spectral/illuminants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "photon/shading/color_math.h"
#include "photon/spectral/dispersion.h"

namespace photon::spectral {
namespace illuminants_test {
namespace {

TEST(SpectralBlackbody, PlanckValuesAndPeakNormalisation) {
  // Planck at 500 nm, 5800 K: 2hc^2 / l^5 / (exp(hc / (l k T)) - 1) = 2.68822e13 W/(m^2 sr m).
  EXPECT_NEAR(blackbody(500.0f, 5800.0f) / 2.68822e13f, 1.0f, 1e-4f);
  for (float t : {1000.0f, 2856.0f, 5000.0f, 6504.0f, 12000.0f}) {
    const float peak = 2.897771955e6f / t;  // Wien, nm
    EXPECT_NEAR(blackbody_normalized(peak, t), 1.0f, 1e-5f) << t;
    for (float l = 200.0f; l < 5000.0f; l += 13.0f)
      EXPECT_LE(blackbody_normalized(l, t), 1.0f + 1e-6f);
  }
  EXPECT_EQ(blackbody(500.0f, 0.0f), 0.0f);
  EXPECT_EQ(blackbody(500.0f, -10.0f), 0.0f);
  EXPECT_EQ(blackbody(500.0f, std::nanf("")), 0.0f);
  EXPECT_EQ(blackbody_normalized(500.0f, INFINITY), 0.0f);
}

// Blender's Blackbody node (Cycles' fit, photon/shading/color_math.h) against Planck's law
// integrated with the CIE observer, both scaled to luminance 1: the fit tracks the Planckian
// locus in Rec.709 to within kBlackbodyTolerance (relative to the largest component) from
// 1200 K to 12000 K; measured 0.0013 (at 6400 K).
constexpr float kBlackbodyTolerance = 0.005f;

TEST(SpectralBlackbody, MatchesBlenderBlackbodyNode) {
  float worst = 0.0f, worst_t = 0.0f;
  for (float t = 1200.0f; t <= 12000.0f; t += 100.0f) {
    const Vec3 ours = blackbody_rec709_chroma(t);
    Vec3 blender = blackbody_rec709(t);
    blender = blender / luminance(blender);
    const float e = max_abs_component(ours - blender) / max_component(ours);
    if (e > worst) worst = e, worst_t = t;
  }
  std::printf("blackbody vs Blender node: max relative difference %.4f at %.0f K\n", worst,
              worst_t);
  EXPECT_LT(worst, kBlackbodyTolerance);
  // 6504 K is close to D65 (not on it: D65 lies off the Planckian locus).
  const Vec3 near_white = blackbody_rec709_chroma(6504.0f);
  EXPECT_NEAR(near_white.x, 1.0f, 0.1f);
  EXPECT_NEAR(near_white.z, 1.0f, 0.1f);
  // Warm below, cool above.
  EXPECT_GT(blackbody_rec709_chroma(2000.0f).x, blackbody_rec709_chroma(2000.0f).z);
  EXPECT_LT(blackbody_rec709_chroma(10000.0f).x, blackbody_rec709_chroma(10000.0f).z);
}

TEST(SpectralDispersion, CauchyReproducesNdAndAbbe) {
  for (float nd : {1.33f, 1.5168f, 1.7f, 2.42f})
    for (float v : {20.0f, 40.0f, 64.17f, 90.0f}) {
      const auto d = CauchyDispersion::from_abbe(nd, v);
      EXPECT_NEAR(d.ior(kLambdaD), nd, 1e-6f);
      const double abbe = (d.ior(kLambdaD) - 1.0) / (double(d.ior(kLambdaF)) - d.ior(kLambdaC));
      EXPECT_NEAR(abbe / v, 1.0, 1e-4) << nd << " " << v;
      EXPECT_GT(d.ior(450.0f), d.ior(650.0f));  // normal dispersion
    }
  // V = 0 (or bad) means no dispersion.
  for (float v : {0.0f, -3.0f, std::nanf(""), INFINITY}) {
    const auto d = CauchyDispersion::from_abbe(1.45f, v);
    EXPECT_FLOAT_EQ(d.ior(400.0f), 1.45f);
    EXPECT_FLOAT_EQ(d.ior(800.0f), 1.45f);
  }
}

// An Abbe number of 0.001 gave indices from -339 to 1137 across the visible range: numbers
// outside real materials' range are taken at its ends, so every wavelength's index stays near n_d.
TEST(SpectralDispersion, AbsurdAbbeNumbersAreTakenAtRealMaterialsEnds) {
  EXPECT_FLOAT_EQ(physical_abbe(0.001f), kMinAbbe);
  EXPECT_FLOAT_EQ(physical_abbe(1e6f), kMaxAbbe);
  EXPECT_FLOAT_EQ(physical_abbe(55.0f), 55.0f);
  EXPECT_FLOAT_EQ(physical_abbe(-1.0f), 0.0f);
  for (float nd : {1.05f, 1.5f, 2.42f})
    for (float v : {1e-3f, 0.5f, kMinAbbe}) {
      const auto d = CauchyDispersion::from_abbe(nd, v);
      const auto rutile = CauchyDispersion::from_abbe(nd, kMinAbbe);
      for (float lambda : {360.0f, 450.0f, 650.0f, 830.0f}) {
        EXPECT_FLOAT_EQ(d.ior(lambda), rutile.ior(lambda));
        // Cauchy's law at V = 9: n - 1 stays within [0.9, 1.3] of n_d - 1.
        EXPECT_GT(d.ior(lambda), 1.0f + 0.9f * (nd - 1.0f)) << nd << " " << v << " " << lambda;
        EXPECT_LT(d.ior(lambda), 1.0f + 1.3f * (nd - 1.0f)) << nd << " " << v << " " << lambda;
      }
    }
}

TEST(SpectralDispersion, CauchyFitOfBk7MatchesSellmeier) {
  // Schott N-BK7: n_d = 1.5168, V = 64.17; Sellmeier indices 1.52532 (450 nm), 1.51452 (650 nm).
  const auto d = CauchyDispersion::from_abbe(1.5168f, 64.17f);
  EXPECT_NEAR(d.ior(450.0f), 1.52532f, 5e-4f);
  EXPECT_NEAR(d.ior(650.0f), 1.51452f, 5e-4f);
}

TEST(SpectralDispersion, PrismSpreadsBlueMoreThanRed) {
  const double apex = 60.0 * M_PI / 180.0;
  const auto d = CauchyDispersion::from_abbe(1.5168f, 64.17f);
  const double n450 = d.ior(450.0f), n650 = d.ior(650.0f);
  // At the symmetric passage the deviation is the minimum one.
  const double inc = std::asin(n650 * std::sin(apex / 2));
  EXPECT_NEAR(prism_deviation(n650, apex, inc), prism_min_deviation(n650, apex), 1e-9);
  EXPECT_LE(prism_min_deviation(n650, apex), prism_deviation(n650, apex, inc + 0.05));
  // 60-degree BK7 prism, 50-degree incidence: blue deviates more than red, by ~0.9 degrees
  // (Sellmeier indices give 0.90 degrees).
  const double in = 50.0 * M_PI / 180.0;
  const double spread =
      (prism_deviation(n450, apex, in) - prism_deviation(n650, apex, in)) * 180.0 / M_PI;
  std::printf("BK7 60-degree prism at 50-degree incidence: 450 nm - 650 nm deviation %.3f deg\n",
              spread);
  const double sellmeier =
      (prism_deviation(1.52532, apex, in) - prism_deviation(1.51452, apex, in)) * 180.0 / M_PI;
  EXPECT_GT(spread, 0.0);
  EXPECT_NEAR(spread, sellmeier, 0.05);
  // Total internal reflection at the second face: NaN.
  EXPECT_TRUE(std::isnan(prism_deviation(1.5, apex, 0.0)));
}

}  // namespace
}  // namespace illuminants_test
}  // namespace photon::spectral

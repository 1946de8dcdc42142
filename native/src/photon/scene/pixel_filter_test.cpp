// The pixel filter's importance sampling: sampled offsets are distributed as the normalized filter
// function (chi-square over bins of the support, and the Kolmogorov-Smirnov distance of the CDF),
// with Cycles' widths, and the width is clamped to Cycles' range.
#include "photon/scene/pixel_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace photon {
namespace pixel_filter_test {
namespace {

// Integral of the filter over [a, b] (midpoint rule, fine enough for 1e-7 relative accuracy).
double filter_integral(PixelFilterType type, float width, double a, double b) {
  constexpr int kSteps = 400;
  const double h = (b - a) / kSteps;
  double sum = 0.0;
  for (int k = 0; k < kSteps; ++k)
    sum += pixel_filter_value(type, width, static_cast<float>(a + (k + 0.5) * h));
  return sum * h;
}

struct Case {
  PixelFilterType type;
  float width;
};

class PixelFilterDistribution : public testing::TestWithParam<Case> {};

// Pearson's chi-square of 200k sampled offsets in 64 bins of the support against the integral
// of the filter over each bin; bins expecting fewer than 20 samples are pooled into one. The
// limit is the 1e-4 upper quantile of chi-square with <= 63 degrees of freedom (about 110).
TEST_P(PixelFilterDistribution, OffsetsFollowTheFilter) {
  const Case c = GetParam();
  const PixelFilter filter(c.type, c.width);
  const double half = 0.5 * pixel_filter_support(c.type, c.width);
  constexpr int kBins = 64, kSamples = 200000;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
  std::vector<double> offsets;
  offsets.reserve(kSamples);
  for (int n = 0; n < kSamples; ++n) {
    const double x = filter.sample_1d(std::min(uniform(rng), 0.99999994f)) - 0.5;
    ASSERT_LE(std::abs(x), half * (1.0 + 1e-5)) << "offset outside the filter's support";
    offsets.push_back(x);
    const int bin = std::clamp(static_cast<int>((x + half) / (2.0 * half) * kBins), 0, kBins - 1);
    observed[bin] += 1.0;
  }
  const double total = filter_integral(c.type, c.width, -half, half);
  for (int b = 0; b < kBins; ++b) {
    const double a = -half + 2.0 * half * b / kBins, e = -half + 2.0 * half * (b + 1) / kBins;
    expected[b] = kSamples * filter_integral(c.type, c.width, a, e) / total;
  }
  double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
  for (int b = 0; b < kBins; ++b) {
    if (expected[b] < 20.0) {
      pooled_o += observed[b];
      pooled_e += expected[b];
      continue;
    }
    chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
  }
  if (pooled_e > 0.0) chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
  EXPECT_LT(chi2, 110.0);

  // Kolmogorov-Smirnov: the largest gap between the empirical and the exact CDF; the 1e-4
  // critical value for 200k samples is 1.95 / sqrt(200k) = 0.0044.
  std::sort(offsets.begin(), offsets.end());
  double ks = 0.0, cdf = 0.0, at = -half;
  constexpr int kProbes = 256;
  size_t below = 0;
  for (int p = 1; p <= kProbes; ++p) {
    const double x = -half + 2.0 * half * p / kProbes;
    cdf += filter_integral(c.type, c.width, at, x) / total;
    at = x;
    while (below < offsets.size() && offsets[below] <= x) ++below;
    ks = std::max(ks, std::abs(static_cast<double>(below) / kSamples - cdf));
  }
  EXPECT_LT(ks, 0.0044);
}

INSTANTIATE_TEST_SUITE_P(Filters, PixelFilterDistribution,
                         testing::Values(Case{PixelFilterType::kBlackmanHarris, 1.5f},
                                         Case{PixelFilterType::kBlackmanHarris, 0.3f},
                                         Case{PixelFilterType::kBlackmanHarris, 10.0f},
                                         Case{PixelFilterType::kGaussian, 1.5f},
                                         Case{PixelFilterType::kGaussian, 4.0f},
                                         Case{PixelFilterType::kBox, 2.0f},
                                         Case{PixelFilterType::kBox, 0.5f}));

// Cycles' widths: the Gaussian's sigma is a quarter of the width, Blackman-Harris reaches one
// width either side of the centre, Box half a width.
TEST(PixelFilter, CyclesWidths) {
  for (const float w : {0.5f, 1.5f, 3.0f}) {
    const PixelFilter gaussian(PixelFilterType::kGaussian, w);
    double sum2 = 0.0;
    constexpr int kN = 100000;
    for (int n = 0; n < kN; ++n) {
      const double x = gaussian.sample_1d((n + 0.5f) / kN) - 0.5;
      sum2 += x * x;
    }
    EXPECT_NEAR(std::sqrt(sum2 / kN), w / 4.0, 2e-3 * w) << w;
    EXPECT_FLOAT_EQ(pixel_filter_support(PixelFilterType::kBlackmanHarris, w), 2.0f * w);
    EXPECT_FLOAT_EQ(pixel_filter_support(PixelFilterType::kGaussian, w), 3.0f * w);
    EXPECT_FLOAT_EQ(pixel_filter_support(PixelFilterType::kBox, w), w);
    // Blackman-Harris peaks at the centre (1.0 up to its coefficients' rounding), ~0 at the ends.
    EXPECT_NEAR(pixel_filter_value(PixelFilterType::kBlackmanHarris, w, 0.0f), 1.0f, 1e-5f);
    EXPECT_NEAR(pixel_filter_value(PixelFilterType::kBlackmanHarris, w, w), 6e-5f, 1e-5f);
    EXPECT_EQ(pixel_filter_value(PixelFilterType::kBlackmanHarris, w, 1.01f * w), 0.0f);
  }
}

// The sampled offsets are odd in u: a pixel's samples are centred on it (no half-pixel shift).
TEST(PixelFilter, CentredOnThePixel) {
  for (const PixelFilterType type :
       {PixelFilterType::kGaussian, PixelFilterType::kBlackmanHarris}) {
    const PixelFilter filter(type, 1.5f);
    EXPECT_NEAR(filter.sample_1d(0.5f), 0.5f, 1e-6f);
    for (int n = 0; n < 1000; ++n) {
      const float u = n / 1000.0f;
      EXPECT_NEAR(filter.sample_1d(u) - 0.5f, 0.5f - filter.sample_1d(1.0f - u), 2e-5f) << u;
      if (n) EXPECT_GE(filter.sample_1d(u), filter.sample_1d((n - 1) / 1000.0f));
    }
  }
}

// Box keeps the historic jitter exactly, so box images render bit-identically.
TEST(PixelFilter, BoxKeepsTheExactJitter) {
  const PixelFilter unit(PixelFilterType::kBox, 1.0f), wide(PixelFilterType::kBox, 2.0f);
  for (int n = 0; n < 1000; ++n) {
    const float u = n / 1000.0f;
    EXPECT_EQ(unit.sample_1d(u), u);
    EXPECT_EQ(wide.sample_1d(u), 0.5f + (u - 0.5f) * 2.0f);
  }
}

// Widths outside Cycles' range [0.01, 10] are clamped; NaN is one pixel.
TEST(PixelFilter, WidthIsClamped) {
  EXPECT_EQ(PixelFilter(PixelFilterType::kBox, 100.0f).width(), 10.0f);
  EXPECT_EQ(PixelFilter(PixelFilterType::kBox, 0.0f).width(), 0.01f);
  EXPECT_EQ(PixelFilter(PixelFilterType::kGaussian, -3.0f).width(), 0.01f);
  EXPECT_EQ(PixelFilter(PixelFilterType::kBlackmanHarris, std::numeric_limits<float>::quiet_NaN())
                .width(),
            1.0f);
  EXPECT_EQ(
      PixelFilter(PixelFilterType::kBlackmanHarris, std::numeric_limits<float>::infinity()).width(),
      10.0f);
  // A clamped Blackman-Harris of width 10 reaches 10 px from the centre and no further.
  const PixelFilter wide(PixelFilterType::kBlackmanHarris, 1e6f);
  EXPECT_NEAR(wide.sample_1d(0.0f) - 0.5f, -10.0f, 0.2f);
  EXPECT_GE(wide.sample_1d(0.0f) - 0.5f, -10.0f);
  EXPECT_NEAR(wide.sample_1d(0.99999994f) - 0.5f, 10.0f, 0.2f);
  // The narrowest filter samples the pixel's centre.
  const PixelFilter narrow(PixelFilterType::kBlackmanHarris, 0.0f);
  EXPECT_NEAR(narrow.sample_1d(0.1f), 0.5f, 0.01f);
}

}  // namespace
}  // namespace pixel_filter_test
}  // namespace photon

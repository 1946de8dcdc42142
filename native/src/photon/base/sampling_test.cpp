#include "photon/base/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "photon/base/rng.h"

namespace photon {
namespace sampling_test {
namespace {

constexpr int kSampleCount = 200000;
constexpr double kSignificance = 1e-4;
constexpr double kPiD = 3.14159265358979323846;

// Upper-tail quantile z of the standard normal: P(Z > z) = alpha, by bisection on erfc.
double normal_upper_quantile(double alpha) {
  double lo = -10.0, hi = 10.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (0.5 * std::erfc(mid / std::sqrt(2.0)) > alpha)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

// Wilson-Hilferty (1931): (X/k)^(1/3) is close to normal with mean 1 - 2/(9k), variance 2/(9k).
double chi2_quantile(int dof, double alpha) {
  const double k = dof;
  const double z = normal_upper_quantile(alpha);
  const double c = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * c * c * c;
}

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double threshold = 0.0;
  bool sample_outside_support = false;
};

// Pearson's test against expected counts; bins expecting fewer than 5 samples are pooled.
ChiSquareResult chi_square(const std::vector<double>& observed,
                           const std::vector<double>& expected) {
  ChiSquareResult r;
  double pooled_obs = 0.0, pooled_exp = 0.0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] <= 0.0) {
      if (observed[i] > 0.0) r.sample_outside_support = true;
      continue;
    }
    if (expected[i] < 5.0) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      continue;
    }
    const double d = observed[i] - expected[i];
    r.statistic += d * d / expected[i];
    ++bins;
  }
  if (pooled_exp > 0.0) {
    const double d = pooled_obs - pooled_exp;
    r.statistic += d * d / pooled_exp;
    ++bins;
  }
  r.dof = bins - 1;
  r.threshold = chi2_quantile(std::max(r.dof, 1), kSignificance);
  return r;
}

void expect_fits(const std::vector<double>& observed, const std::vector<double>& expected) {
  double total_expected = 0.0;
  for (double e : expected) total_expected += e;
  // The expected counts come from integrating the pdf: they must account for every sample.
  EXPECT_NEAR(total_expected, kSampleCount, 1e-3 * kSampleCount);
  const ChiSquareResult r = chi_square(observed, expected);
  EXPECT_FALSE(r.sample_outside_support) << "samples landed where the pdf is zero";
  EXPECT_GT(r.dof, 10);
  EXPECT_LT(r.statistic, r.threshold)
      << "chi-square statistic " << r.statistic << " with " << r.dof << " degrees of freedom";
}

// Fixed-seed uniform points on [0, 1)^2 (24-bit floats, never 1).
class UniformSquare {
 public:
  explicit UniformSquare(uint32_t seed) : rng_(seed) {}
  Vec2 next() {
    const float a = static_cast<float>(rng_() >> 8) * (1.0f / 16777216.0f);
    const float b = static_cast<float>(rng_() >> 8) * (1.0f / 16777216.0f);
    return {a, b};
  }

 private:
  std::mt19937 rng_;
};

double azimuth(const Vec3& w) {
  double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
  return phi < 0.0 ? phi + 2.0 * kPiD : phi;
}

int bin_of(double x, double lo, double hi, int n) {
  return std::clamp(static_cast<int>((x - lo) / (hi - lo) * n), 0, n - 1);
}

// Histograms directions over (theta, phi) cells with theta in [0, theta_max] and checks them
// against the integral of a pdf that depends on theta only: P(cell) = dphi * F(theta0, theta1).
void check_direction_distribution(const std::function<Vec3(Vec2)>& sample, double theta_max,
                                  const std::function<double(double, double)>& theta_integral,
                                  uint32_t seed) {
  const int kTheta = 20, kPhi = 40;
  std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
  UniformSquare rng(seed);
  for (int i = 0; i < kSampleCount; ++i) {
    const Vec3 w = sample(rng.next());
    ASSERT_NEAR(length(w), 1.0f, 1e-5f);
    const double theta = std::acos(std::clamp(static_cast<double>(w.z), -1.0, 1.0));
    ASSERT_LE(theta, theta_max + 1e-3);
    ++observed[bin_of(theta, 0.0, theta_max, kTheta) * kPhi +
               bin_of(azimuth(w), 0, 2 * kPiD, kPhi)];
  }
  const double dphi = 2.0 * kPiD / kPhi;
  for (int t = 0; t < kTheta; ++t) {
    const double t0 = theta_max * t / kTheta, t1 = theta_max * (t + 1) / kTheta;
    for (int p = 0; p < kPhi; ++p)
      expected[t * kPhi + p] = kSampleCount * dphi * theta_integral(t0, t1);
  }
  expect_fits(observed, expected);
}

TEST(ChiSquare, WilsonHilfertyQuantileIsAccurate) {
  // Reference points: for dof = 2 the chi-square tail is exp(-x/2), so x = -2 ln(alpha); for
  // large dof the Cornish-Fisher expansion gives k + z sqrt(2k) + 2 (z^2 - 1) / 3 + O(1/sqrt(k)).
  EXPECT_NEAR(chi2_quantile(2, 0.01), -2.0 * std::log(0.01), 0.1);
  EXPECT_NEAR(normal_upper_quantile(0.5), 0.0, 1e-9);
  EXPECT_NEAR(0.5 * std::erfc(normal_upper_quantile(1e-4) / std::sqrt(2.0)), 1e-4, 1e-12);
  const double k = 10000.0, z = normal_upper_quantile(1e-4);
  EXPECT_NEAR(chi2_quantile(10000, 1e-4), k + z * std::sqrt(2.0 * k) + 2.0 * (z * z - 1) / 3.0,
              0.5);
}

TEST(ChiSquare, RejectsAWrongDistribution) {
  // Sanity check of the harness: uniform hemisphere samples are not cosine distributed.
  const int kTheta = 20, kPhi = 40;
  std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
  UniformSquare rng(7);
  for (int i = 0; i < kSampleCount; ++i) {
    Vec3 w = sample_uniform_sphere(rng.next());
    w.z = std::fabs(w.z);
    const double theta = std::acos(std::clamp(static_cast<double>(w.z), -1.0, 1.0));
    ++observed[bin_of(theta, 0.0, kPiD / 2, kTheta) * kPhi + bin_of(azimuth(w), 0, 2 * kPiD, kPhi)];
  }
  for (int t = 0; t < kTheta; ++t) {
    const double s0 = std::sin(kPiD / 2 * t / kTheta), s1 = std::sin(kPiD / 2 * (t + 1) / kTheta);
    for (int p = 0; p < kPhi; ++p)
      expected[t * kPhi + p] = kSampleCount * (2 * kPiD / kPhi) * (s1 * s1 - s0 * s0) / (2 * kPiD);
  }
  const ChiSquareResult r = chi_square(observed, expected);
  EXPECT_GT(r.statistic, r.threshold);
}

TEST(Sampling, CosineHemisphereIsCosineDistributed) {
  // pdf(w) = cos(theta) / pi; over a cell: dphi / pi * int cos sin dtheta = dphi (s1^2 - s0^2) /
  // 2pi.
  check_direction_distribution(
      sample_cosine_hemisphere, kPiD / 2,
      [](double t0, double t1) {
        const double s0 = std::sin(t0), s1 = std::sin(t1);
        return (s1 * s1 - s0 * s0) / (2.0 * kPiD);
      },
      1);
}

TEST(Sampling, CosineHemisphereStaysAboveTheHorizonAndMatchesItsPdf) {
  UniformSquare rng(11);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 w = sample_cosine_hemisphere(rng.next());
    EXPECT_GE(w.z, 0.0f);
    EXPECT_NEAR(length(w), 1.0f, 1e-5f);
  }
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(1.0f), 1.0f / kPi);
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(0.5f), 0.5f / kPi);
  EXPECT_EQ(cosine_hemisphere_pdf(-0.5f), 0.0f);
}

TEST(Sampling, UniformSphereIsUniform) {
  // pdf 1 / 4pi; over a cell: dphi (cos t0 - cos t1) / 4pi.
  check_direction_distribution(
      sample_uniform_sphere, kPiD,
      [](double t0, double t1) { return (std::cos(t0) - std::cos(t1)) / (4.0 * kPiD); }, 2);
}

TEST(Sampling, UniformConeIsUniformInsideTheCone) {
  for (double cos_max : {0.3, 0.9, 0.999}) {
    SCOPED_TRACE(cos_max);
    const float cm = static_cast<float>(cos_max);
    check_direction_distribution(
        [cm](Vec2 u) { return sample_uniform_cone(u, cm); }, std::acos(cos_max),
        [cos_max](double t0, double t1) {
          return (std::cos(t0) - std::cos(t1)) / (2.0 * kPiD * (1.0 - cos_max));
        },
        3);
    // The pdf times the cone's solid angle 2 pi (1 - cos_max) is one.
    EXPECT_NEAR(uniform_cone_pdf(cm) * 2.0 * kPiD * (1.0 - cos_max), 1.0, 1e-3);
  }
}

TEST(Sampling, UniformConeStaysInsideTheCone) {
  UniformSquare rng(5);
  const float cos_max = std::cos(0.2f);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 w = sample_uniform_cone(rng.next(), cos_max);
    EXPECT_NEAR(length(w), 1.0f, 1e-5f);
    EXPECT_GE(w.z, cos_max - 1e-6f);
  }
  // The corners of the square map to the axis and to the rim.
  EXPECT_NEAR(sample_uniform_cone(Vec2(0.0f, 0.0f), cos_max).z, 1.0f, 1e-6f);
  EXPECT_NEAR(sample_uniform_cone(Vec2(0.9999999f, 0.3f), cos_max).z, cos_max, 1e-5f);
}

// Area of [x0, x1] x [y0, y1] inside the unit disk (midpoint rule over x on the clipped height).
double cell_area_in_unit_disk(double x0, double x1, double y0, double y1) {
  const int kSteps = 4000;
  const double h = (x1 - x0) / kSteps;
  double area = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = x0 + (i + 0.5) * h;
    const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
    area += std::max(0.0, std::min(y1, s) - std::max(y0, -s)) * h;
  }
  return area;
}

TEST(Sampling, ConcentricDiskIsUniformOnTheDisk) {
  // Cartesian cells (unrelated to the mapping's polar structure); pdf 1 / pi.
  const int kGrid = 20;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  UniformSquare rng(4);
  for (int i = 0; i < kSampleCount; ++i) {
    const Vec2 d = sample_concentric_disk(rng.next());
    ASSERT_LE(d.x * d.x + d.y * d.y, 1.0f + 1e-5f);
    ++observed[bin_of(d.y, -1, 1, kGrid) * kGrid + bin_of(d.x, -1, 1, kGrid)];
  }
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const double x0 = -1.0 + 2.0 * i / kGrid, x1 = -1.0 + 2.0 * (i + 1) / kGrid;
      const double y0 = -1.0 + 2.0 * j / kGrid, y1 = -1.0 + 2.0 * (j + 1) / kGrid;
      expected[j * kGrid + i] = kSampleCount * cell_area_in_unit_disk(x0, x1, y0, y1) / kPiD;
    }
  expect_fits(observed, expected);
}

TEST(Sampling, ConcentricDiskMapsSquareBoundaryToCircle) {
  EXPECT_EQ(sample_concentric_disk(Vec2(0.5f, 0.5f)).x, 0.0f);
  EXPECT_EQ(sample_concentric_disk(Vec2(0.5f, 0.5f)).y, 0.0f);
  for (float t : {0.0f, 0.1f, 0.37f, 0.5f, 0.8f, 1.0f}) {
    for (Vec2 u : {Vec2(t, 0.0f), Vec2(t, 1.0f), Vec2(0.0f, t), Vec2(1.0f, t)}) {
      const Vec2 d = sample_concentric_disk(u);
      EXPECT_NEAR(std::sqrt(d.x * d.x + d.y * d.y), 1.0f, 1e-5f) << u.x << " " << u.y;
    }
  }
}

TEST(Sampling, UniformTriangleBarycentricsAreUniform) {
  // Uniform on {b0, b1 >= 0, b0 + b1 <= 1}: density 2. On a K x K grid over (b0, b1), cells
  // with i + j < K - 1 lie inside, cells with i + j == K - 1 are cut in half by the diagonal.
  const int kGrid = 20;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  const int kMarginal = 25;
  std::vector<double> obs_b[3], exp_b[3];
  for (auto& v : obs_b) v.assign(kMarginal, 0.0);
  for (auto& v : exp_b) v.assign(kMarginal, 0.0);
  UniformSquare rng(6);
  for (int i = 0; i < kSampleCount; ++i) {
    const Vec2 b = sample_uniform_triangle(rng.next());
    const float b2 = 1.0f - b.x - b.y;
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_GE(b2, -1e-6f);
    ++observed[bin_of(b.y, 0, 1, kGrid) * kGrid + bin_of(b.x, 0, 1, kGrid)];
    ++obs_b[0][bin_of(b.x, 0, 1, kMarginal)];
    ++obs_b[1][bin_of(b.y, 0, 1, kMarginal)];
    ++obs_b[2][bin_of(b2, 0, 1, kMarginal)];
  }
  const double cell = 1.0 / (kGrid * kGrid);
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const double area = i + j < kGrid - 1 ? cell : (i + j == kGrid - 1 ? 0.5 * cell : 0.0);
      expected[j * kGrid + i] = kSampleCount * 2.0 * area;
    }
  expect_fits(observed, expected);
  // Each barycentric has the marginal density 2 (1 - b): P(a <= b < c) = (1-a)^2 - (1-c)^2.
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    for (int i = 0; i < kMarginal; ++i) {
      const double a = static_cast<double>(i) / kMarginal,
                   c = static_cast<double>(i + 1) / kMarginal;
      exp_b[k][i] = kSampleCount * ((1 - a) * (1 - a) - (1 - c) * (1 - c));
    }
    const ChiSquareResult r = chi_square(obs_b[k], exp_b[k]);
    EXPECT_FALSE(r.sample_outside_support);
    EXPECT_LT(r.statistic, r.threshold);
  }
}

TEST(Sampler, IsAPureFunctionOfSeedStreamAndSample) {
  for (uint32_t s : {0u, 1u, 12345u}) {
    Sampler a(42, 7, s), b(42, 7, s);
    for (int i = 0; i < 20; ++i) {
      if (i % 3 == 0) {
        EXPECT_EQ(a.get_1d(), b.get_1d());
      } else {
        const Vec2 ua = a.get_2d(), ub = b.get_2d();
        EXPECT_EQ(ua.x, ub.x);
        EXPECT_EQ(ua.y, ub.y);
      }
    }
  }
  // Changing any of the three inputs changes the numbers.
  auto first = [](uint64_t seed, uint64_t stream, uint32_t sample) {
    Sampler s(seed, stream, sample);
    const float x = s.get_1d();
    const Vec2 u = s.get_2d();
    return std::vector<float>{x, u.x, u.y};
  };
  const auto base = first(42, 7, 3);
  EXPECT_NE(base, first(43, 7, 3));
  EXPECT_NE(base, first(42, 8, 3));
  EXPECT_NE(base, first(42, 7, 4));
}

TEST(Sampler, ValuesAreInTheUnitInterval) {
  for (uint64_t stream = 0; stream < 64; ++stream) {
    for (uint32_t s = 0; s < 256; ++s) {
      Sampler sampler(9, stream, s);
      for (int d = 0; d < 4; ++d) {
        const float x = sampler.get_1d();
        EXPECT_GE(x, 0.0f);
        EXPECT_LT(x, 1.0f);
        const Vec2 u = sampler.get_2d();
        ASSERT_GE(u.x, 0.0f);
        ASSERT_LT(u.x, 1.0f);
        ASSERT_GE(u.y, 0.0f);
        ASSERT_LT(u.y, 1.0f);
      }
    }
  }
}

TEST(Sampler, Get2dIsStratifiedOverSampleIndices) {
  // The pixel's kN samples, 64 per cell of a 16 x 16 grid. Independent uniform points would give
  // a chi-square near its 255 degrees of freedom and cells off by +-8 (one standard deviation) or
  // more; a low-discrepancy sequence must do far better.
  const int kGrid = 16, kPerCell = 64, kN = kGrid * kGrid * kPerCell;
  for (uint64_t stream : {0ull, 1234567ull}) {
    for (int dim = 0; dim < 3; ++dim) {
      SCOPED_TRACE(::testing::Message() << "stream " << stream << " dimension " << dim);
      std::vector<int> count(kGrid * kGrid, 0);
      for (int s = 0; s < kN; ++s) {
        Sampler sampler(3, stream, static_cast<uint32_t>(s), static_cast<uint32_t>(kN));
        Vec2 u;
        for (int d = 0; d <= dim; ++d) u = sampler.get_2d();
        ++count[bin_of(u.y, 0, 1, kGrid) * kGrid + bin_of(u.x, 0, 1, kGrid)];
      }
      double chi2 = 0.0;
      int worst = 0;
      for (int c : count) {
        chi2 += static_cast<double>(c - kPerCell) * (c - kPerCell) / kPerCell;
        worst = std::max(worst, std::abs(c - kPerCell));
      }
      EXPECT_LT(chi2, 255.0 / 10.0);
      EXPECT_LE(worst, kPerCell / 8);
    }
  }
}

TEST(Sampler, Stratified1dTakesNoDimensionAndCoversEveryStratum) {
  const uint32_t kN = 256;
  for (uint64_t stream : {0ull, 99ull}) {
    std::vector<int> hits(kN, 0);
    for (uint32_t s = 0; s < kN; ++s) {
      Sampler a(5, stream, s, kN), b(5, stream, s, kN);
      const float u = a.stratified_1d(1);
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      ++hits[static_cast<int>(u * kN)];
      // Other tags give other numbers; the dimension sequence is untouched.
      EXPECT_NE(u, a.stratified_1d(2));
      EXPECT_EQ(a.get_1d(), b.get_1d());
      const Vec2 pa = a.get_2d(), pb = b.get_2d();
      EXPECT_EQ(pa.x, pb.x);
      EXPECT_EQ(pa.y, pb.y);
    }
    for (int h : hits) EXPECT_EQ(h, 1);  // one sample per stratum of 1 / kN
  }
  // Without a sample count: still in [0, 1) and a pure function of its inputs.
  Sampler c(1, 2, 3, 0), d(1, 2, 3, 0);
  EXPECT_EQ(c.stratified_1d(7), d.stratified_1d(7));
  EXPECT_LT(c.stratified_1d(7), 1.0f);
}

// Regression test for a bug in photon/rng.h as of commit 109ae12: every get_2d() dimension
// returned the same R2 point of the sample index, only shifted by a per-(pixel, dimension)
// Cranley-Patterson rotation, so within one pixel the second 2D value was the first plus a
// constant (mod 1). The 4D points (pixel jitter, lens) or (pixel jitter, light sample) then lie
// on a 2D sub-torus and integrands depending on both converge to a wrong, pixel-dependent value
// however many samples are taken (see RenderSession.DepthOfFieldConvergesToTheExactPixelValue).
TEST(Sampler, SuccessiveDimensionsAreIndependentWithinAPixel) {
  const int kGrid = 8, kN = 4096;
  for (uint32_t count : {static_cast<uint32_t>(kN), 0u}) {  // known and unknown sample count
    for (uint64_t pixel = 0; pixel < 4; ++pixel) {
      SCOPED_TRACE(::testing::Message() << "pixel " << pixel << " sample count " << count);
      std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, kN / 64.0);
      double product = 0.0;
      for (int s = 0; s < kN; ++s) {
        Sampler sampler(0, pixel, static_cast<uint32_t>(s), count);
        const Vec2 a = sampler.get_2d();
        const Vec2 b = sampler.get_2d();
        ++observed[bin_of(b.x, 0, 1, kGrid) * kGrid + bin_of(a.x, 0, 1, kGrid)];
        product += (a.x < 0.5f && b.x < 0.5f) ? 1.0 : 0.0;
      }
      // (a.x, b.x) should fill the unit square uniformly.
      const ChiSquareResult r = chi_square(observed, expected);
      EXPECT_LT(r.statistic, r.threshold);
      // E[1(a.x < 1/2) 1(b.x < 1/2)] = 1/4 for independent uniforms; the standard error with
      // 4096 independent samples is 0.007.
      EXPECT_NEAR(product / kN, 0.25, 0.05);
    }
  }
}

TEST(Sampler, PermuteIndexIsABijection) {
  for (uint32_t count : {1u, 2u, 3u, 7u, 64u, 1000u, 4097u}) {
    for (uint32_t key : {0u, 1u, 0xDEADBEEFu, 0x12345678u}) {
      std::vector<int> hits(count, 0);
      for (uint32_t i = 0; i < count; ++i) {
        const uint32_t j = permute_index(i, count, key);
        ASSERT_LT(j, count);
        ++hits[j];
      }
      for (uint32_t j = 0; j < count; ++j) ASSERT_EQ(hits[j], 1) << count << " " << key;
    }
  }
  // Different keys give different orders.
  int same = 0;
  for (uint32_t i = 0; i < 1000; ++i)
    same += permute_index(i, 1000, 1u) == permute_index(i, 1000, 2u);
  EXPECT_LT(same, 50);
}

TEST(Sampler, DifferentStreamsAreUniformAcrossPixels) {
  // The per-pixel rotation makes one sample index uniform across pixels (no pattern shared by
  // all pixels): chi-square over a 10 x 10 grid of the first 2D value of 100k pixels.
  const int kGrid = 10, kPixels = 100000;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, kPixels / 100.0);
  for (int p = 0; p < kPixels; ++p) {
    Sampler sampler(0, static_cast<uint64_t>(p), 0);
    const Vec2 u = sampler.get_2d();
    ++observed[bin_of(u.y, 0, 1, kGrid) * kGrid + bin_of(u.x, 0, 1, kGrid)];
  }
  const ChiSquareResult r = chi_square(observed, expected);
  EXPECT_LT(r.statistic, r.threshold);
}

TEST(Sampling, InvertConcentricDiskIsTheInverse) {
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) {
      const Vec2 u((i + 0.37f) / 32.0f, (j + 0.61f) / 32.0f);
      const Vec2 back = invert_concentric_disk(sample_concentric_disk(u));
      EXPECT_NEAR(back.x, u.x, 1e-4f) << i << "," << j;
      EXPECT_NEAR(back.y, u.y, 1e-4f) << i << "," << j;
    }
}

// Samples taken in consecutive blocks, each stratified among itself (a time-limited render's
// rounds), visit the same R2 points as one block of them all: the same set in each 2D
// dimension, in another order.
TEST(Sampler, ConsecutiveBlocksVisitTheSamePointsAsOneBlock) {
  const auto points = [](const std::vector<std::pair<uint32_t, uint32_t>>& blocks) {
    std::vector<std::pair<float, float>> out;
    for (const auto& [first, count] : blocks)
      for (uint32_t k = first; k < first + count; ++k) {
        Sampler sampler(7, 1234, k, count, first);
        sampler.get_2d();
        const Vec2 p = sampler.get_2d();  // a later dimension, with its own order
        out.emplace_back(p.x, p.y);
      }
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(points({{0, 1}, {1, 2}, {3, 4}, {7, 8}}), points({{0, 15}}));
  // Each block's 1D strata are filled once.
  std::vector<int> strata(8, 0);
  for (uint32_t k = 7; k < 15; ++k)
    ++strata[static_cast<int>(Sampler(7, 1234, k, 8, 7).stratified_1d(5) * 8.0f)];
  for (int n : strata) EXPECT_EQ(n, 1);
}

}  // namespace
}  // namespace sampling_test
}  // namespace photon

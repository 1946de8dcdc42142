// Hero-wavelength sampling (Wilkie et al. 2014) and the Monte Carlo XYZ estimate.
#include "photon/spectral/sampled_spectrum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "photon/spectral/colorimetry.h"
#include "photon/spectral/illuminants.h"

namespace photon::spectral {
namespace sampled_spectrum_test {
namespace {

constexpr float kRange = kLambdaMax - kLambdaMin;

TEST(SpectralSampling, HeroRotationsAreStratified) {
  for (float u : {0.0f, 0.1f, 0.37f, 0.5f, 0.999f}) {
    const auto wl = SampledWavelengths::sample_uniform(u);
    EXPECT_NEAR(wl.lambda(0), kLambdaMin + u * kRange, 1e-3f);
    float sorted[kSpectrumSamples];
    for (int i = 0; i < kSpectrumSamples; ++i) {
      EXPECT_GE(wl.lambda(i), kLambdaMin);
      EXPECT_LE(wl.lambda(i), kLambdaMax);
      EXPECT_FLOAT_EQ(wl.pdf(i), 1.0f / kRange);
      sorted[i] = wl.lambda(i);
    }
    // One wavelength in each of the N equal sub-ranges, all a multiple of range/N apart.
    std::sort(sorted, sorted + kSpectrumSamples);
    for (int i = 1; i < kSpectrumSamples; ++i)
      EXPECT_NEAR(sorted[i] - sorted[i - 1], kRange / kSpectrumSamples, 1e-3f) << u;
    EXPECT_FALSE(wl.secondary_terminated());
  }
}

TEST(SpectralSampling, VisiblePdfIsNormalisedAndInverted) {
  double integral = 0.0;
  for (int i = 0; i < 47000; ++i)
    integral += visible_wavelength_pdf(kLambdaMin + (i + 0.5f) * 0.01f) * 0.01;
  EXPECT_NEAR(integral, 1.0, 1e-4);
  EXPECT_EQ(visible_wavelength_pdf(300.0f), 0.0f);
  // The CDF at the sampled wavelength gives back u.
  for (float u : {0.01f, 0.25f, 0.5f, 0.75f, 0.99f}) {
    const float lambda = sample_visible_wavelength(u);
    double cdf = 0.0;
    const int steps = 20000;
    const double h = (lambda - kLambdaMin) / steps;
    for (int i = 0; i < steps; ++i) cdf += visible_wavelength_pdf(kLambdaMin + (i + 0.5) * h) * h;
    EXPECT_NEAR(cdf, u, 1e-4) << u;
  }
  EXPECT_FLOAT_EQ(sample_visible_wavelength(0.0f), kLambdaMin);
  EXPECT_FLOAT_EQ(sample_visible_wavelength(1.0f), kLambdaMax);
}

TEST(SpectralSampling, TerminateSecondaryKeepsOneSampleEstimator) {
  auto wl = SampledWavelengths::sample_uniform(0.3f);
  const float pdf0 = wl.pdf(0);
  wl.terminate_secondary();
  EXPECT_TRUE(wl.secondary_terminated());
  EXPECT_FLOAT_EQ(wl.pdf(0), pdf0 / kSpectrumSamples);
  for (int i = 1; i < kSpectrumSamples; ++i) EXPECT_EQ(wl.pdf(i), 0.0f);
  wl.terminate_secondary();  // idempotent
  EXPECT_FLOAT_EQ(wl.pdf(0), pdf0 / kSpectrumSamples);
  // safe_div drops the terminated wavelengths.
  const SampledSpectrum q = SampledSpectrum(2.0f).safe_div(wl.pdf());
  EXPECT_FLOAT_EQ(q[0], 2.0f / wl.pdf(0));
  for (int i = 1; i < kSpectrumSamples; ++i) EXPECT_EQ(q[i], 0.0f);
}

TEST(SpectralSampling, FewerWavelengthsThanLanesKeepTheEstimatorNormalised) {
  for (int n = 1; n <= kSpectrumSamples; ++n) {
    auto wl = SampledWavelengths::sample_visible(0.2f, n);
    EXPECT_EQ(wl.active_count(), n);
    for (int i = 0; i < kSpectrumSamples; ++i) {
      EXPECT_EQ(wl.active(i), i < n);
      EXPECT_GE(wl.lambda(i), kLambdaMin);
      EXPECT_LE(wl.lambda(i), kLambdaMax);
    }
    // The used wavelengths are the n-stratified visible samples, pdf scaled by n / N.
    for (int i = 0; i < n; ++i) {
      const float u = 0.2f + static_cast<float>(i) / n;
      EXPECT_NEAR(wl.lambda(i), sample_visible_wavelength(u - std::floor(u)), 1e-2f);
      EXPECT_NEAR(wl.pdf(i), visible_wavelength_pdf(wl.lambda(i)) * n / kSpectrumSamples, 1e-6f);
    }
    // A constant spectrum of 1: every wavelength estimates the same, so the estimate is exact
    // up to the shape of the colour matching functions; the Y averaged over u must be 1.
    double y = 0.0;
    const int count = 4000;
    for (int k = 0; k < count; ++k) {
      auto w = SampledWavelengths::sample_visible((k + 0.5f) / count, n);
      if (k % 2) w.terminate_secondary();
      y += sampled_to_xyz(SampledSpectrum(1.0f), w).y;
    }
    EXPECT_NEAR(y / count, 1.0, 2e-3) << n;
  }
  // A single wavelength of its own pdf (a photon's) estimates L / pdf alone.
  const auto one = SampledWavelengths::single(550.0f, 0.004f);
  EXPECT_EQ(one.active_count(), 1);
  EXPECT_TRUE(one.secondary_terminated());
  const Vec3 xyz = sampled_to_xyz(SampledSpectrum(1.0f), one);
  EXPECT_NEAR(xyz.y, cie_xyz(550.0f).y / (0.004f * cie_y_integral()), 1e-4f);
}

// Mean and per-estimate standard deviation (in Rec.709) of the XYZ estimate of `s` over
// `count` stratified u.
struct Estimate {
  Vec3 mean;
  float stddev;
};
template <class Sampler>
Estimate estimate(const TabulatedSpectrum& s, int count, Sampler sample, bool terminate) {
  Vec3 sum(0.0f);
  double sq = 0.0;
  const Vec3 exact = xyz_to_rec709(emission_to_xyz(s));
  for (int k = 0; k < count; ++k) {
    auto wl = sample((k + 0.5f) / count);
    if (terminate) wl.terminate_secondary();
    const Vec3 rgb = xyz_to_rec709(sampled_to_xyz(s.sample(wl), wl));
    sum += rgb;
    const Vec3 d = rgb - exact;
    sq += dot(d, d);
  }
  return {sum / static_cast<float>(count), static_cast<float>(std::sqrt(sq / count / 3.0))};
}

TEST(SpectralSampling, MonteCarloXyzConvergesToTheTableIntegral) {
  const auto uniform = [](float u) { return SampledWavelengths::sample_uniform(u); };
  const auto visible = [](float u) { return SampledWavelengths::sample_visible(u); };
  for (Illuminant which : {Illuminant::kD65, Illuminant::kA, Illuminant::kF11}) {
    const auto& s = illuminant_spectrum(which);
    const Vec3 exact = xyz_to_rec709(emission_to_xyz(s));
    for (bool terminate : {false, true}) {
      const Estimate eu = estimate(s, 20000, uniform, terminate);
      const Estimate ev = estimate(s, 20000, visible, terminate);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(eu.mean[c], exact[c], 2e-3f) << static_cast<int>(which) << " " << c;
        EXPECT_NEAR(ev.mean[c], exact[c], 2e-3f) << static_cast<int>(which) << " " << c;
      }
      std::printf("illuminant %d%s: per-path RGB std dev uniform %.4f, visible %.4f\n",
                  static_cast<int>(which), terminate ? " (hero only)" : "", eu.stddev, ev.stddev);
      // Importance sampling by the eye's response must help on smooth spectra.
      if (which != Illuminant::kF11) {
        EXPECT_LT(ev.stddev, eu.stddev);
      }
    }
  }
}

TEST(SpectralSampling, HeroSamplesBeatOneWavelength) {
  // Wilkie et al.'s point: N rotated wavelengths per path cost one path but cut the colour
  // noise well below a single wavelength's (a factor near sqrt(N) or better, by stratification).
  const auto& s = illuminant_spectrum(Illuminant::kD65);
  const Estimate hero = estimate(
      s, 20000, [](float u) { return SampledWavelengths::sample_uniform(u); }, false);
  const Estimate single = estimate(
      s, 20000, [](float u) { return SampledWavelengths::sample_uniform(u); }, true);
  EXPECT_LT(hero.stddev * std::sqrt(static_cast<float>(kSpectrumSamples)), single.stddev);
}

TEST(SpectralSampling, SpectrumArithmetic) {
  SampledSpectrum a(2.0f), b(4.0f);
  b[1] = 0.0f;
  EXPECT_FLOAT_EQ((a * b)[0], 8.0f);
  EXPECT_FLOAT_EQ((a + b)[1], 2.0f);
  EXPECT_FLOAT_EQ((a - b)[2], -2.0f);
  EXPECT_FLOAT_EQ((0.5f * a)[3], 1.0f);
  EXPECT_EQ(a.safe_div(b)[1], 0.0f);
  EXPECT_FLOAT_EQ(a.safe_div(b)[0], 0.5f);
  EXPECT_FLOAT_EQ(b.max_value(), 4.0f);
  EXPECT_FLOAT_EQ(b.average(), 3.0f);
  EXPECT_FALSE(b.is_black());
  EXPECT_TRUE(SampledSpectrum().is_black());
  EXPECT_FLOAT_EQ((a / 4.0f)[2], 0.5f);
  EXPECT_TRUE(is_finite(a));
  EXPECT_FALSE(is_finite(a * SampledSpectrum(INFINITY)));
  EXPECT_FALSE(is_black(b));
  EXPECT_FLOAT_EQ(max_component(b), 4.0f);
}

}  // namespace
}  // namespace sampled_spectrum_test
}  // namespace photon::spectral

#include "photon/lights/area_spread.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace photon {
namespace area_spread_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Integral over the hemisphere of cos * a, by midpoint quadrature in theta.
double hemisphere_integral(const AreaSpread& s, int steps = 200000) {
  double sum = 0.0;
  const double dt = 0.5 * kPiD / steps;
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) * dt;
    sum +=
        std::cos(theta) * s.attenuation(static_cast<float>(std::cos(theta))) * std::sin(theta) * dt;
  }
  return 2.0 * kPiD * sum;
}

TEST(AreaSpread, KeepsTheLampsPowerForEverySpread) {
  // cos * a integrates to pi, as cos alone does, so the lamp's power does not change.
  for (float degrees : {1.0f, 3.0f, 5.7f, 6.0f, 20.0f, 60.0f, 120.0f, 179.0f}) {
    const AreaSpread s(degrees * kPi / 180.0f);
    ASSERT_TRUE(s.active());
    EXPECT_NEAR(hemisphere_integral(s), kPiD, 2e-3 * kPiD) << degrees;
  }
}

TEST(AreaSpread, IsCyclesSoftBoxProfile) {
  // Cycles 3.4 (scene/light.cpp): tan_spread = tan((pi - spread) / 2), normalize_spread =
  // 2 / (2 + (pi - spread - pi) tan_spread), a = (1 - tan_spread tan theta) normalize_spread.
  for (float degrees : {10.0f, 45.0f, 90.0f, 150.0f}) {
    const float spread = degrees * kPi / 180.0f;
    const AreaSpread s(spread);
    const double angle = 0.5 * (kPiD - spread), tan_spread = std::tan(angle);
    const double normalize = 2.0 / (2.0 + (2.0 * angle - kPiD) * tan_spread);
    for (float theta_deg : {0.0f, 2.0f, 4.0f, 20.0f, 40.0f, 70.0f, 89.0f}) {
      const double theta = theta_deg * kPiD / 180.0;
      const double cycles = std::max(0.0, (1.0 - tan_spread * std::tan(theta)) * normalize);
      EXPECT_NEAR(s.attenuation(static_cast<float>(std::cos(theta))), cycles,
                  1e-4 * std::max(1.0, cycles))
          << degrees << " " << theta_deg;
    }
  }
}

TEST(AreaSpread, TheWholeHemisphereOrNaNIsALambertianLamp) {
  for (float spread : {kPi, 4.0f, NAN}) {
    const AreaSpread s(spread);
    EXPECT_FALSE(s.active());
    EXPECT_EQ(s.attenuation(0.3f), 1.0f);
  }
  // Narrower than a degree is a degree, as in Cycles 3.x.
  const AreaSpread zero(0.0f), one(AreaSpread::kMinSpread);
  EXPECT_EQ(zero.half_angle(), one.half_angle());
  EXPECT_GT(zero.attenuation(1.0f), 0.0f);
}

TEST(AreaSpread, SampledDirectionsFollowTheDensity) {
  // Histogram of cos theta from a 512 x 512 grid of u against the density integrated over each
  // bin; every direction lies within the spread and its pdf is positive.
  for (float degrees : {2.0f, 30.0f, 100.0f, 170.0f}) {
    const AreaSpread s(degrees * kPi / 180.0f);
    const double cos_h = std::cos(s.half_angle());
    constexpr int kBins = 16, kN = 512;
    std::vector<double> hist(kBins, 0.0);
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) {
        const Vec3 d = s.sample_direction(Vec2((i + 0.5f) / kN, (j + 0.5f) / kN));
        ASSERT_NEAR(length(d), 1.0f, 1e-5f);
        ASSERT_GE(d.z, cos_h - 1e-6);
        const int bin = std::min(kBins - 1, static_cast<int>((1.0 - d.z) / (1.0 - cos_h) * kBins));
        hist[bin] += 1.0 / (static_cast<double>(kN) * kN);
      }
    for (int b = 0; b < kBins; ++b) {
      // P(bin) = integral of 2 pi pdf over cos theta in the bin.
      const double z_hi = 1.0 - b * (1.0 - cos_h) / kBins;
      const double z_lo = 1.0 - (b + 1) * (1.0 - cos_h) / kBins;
      double expected = 0.0;
      const int steps = 2000;
      for (int k = 0; k < steps; ++k) {
        const double z = z_lo + (k + 0.5) * (z_hi - z_lo) / steps;
        expected += 2.0 * kPiD * s.pdf(static_cast<float>(z)) * (z_hi - z_lo) / steps;
      }
      EXPECT_NEAR(hist[b], expected, 2e-3 + 0.01 * expected) << degrees << " bin " << b;
    }
  }
}

}  // namespace
}  // namespace area_spread_test
}  // namespace photon

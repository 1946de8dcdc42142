// Beckmann's microfacet functions: the distribution is normalised, the visible-normal density
// integrates to one (so its exact Lambda is right), Walter's approximation stays near it, the
// values are Cycles' formulas, and the inverse error function inverts std::erf.
#include "photon/base/microfacet_beckmann.h"

#include <gtest/gtest.h>

#include <cmath>

namespace photon {
namespace microfacet_beckmann_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

Vec3 spherical(double theta, double phi) {
  return Vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
              static_cast<float>(std::sin(theta) * std::sin(phi)),
              static_cast<float>(std::cos(theta)));
}

// Midpoint quadrature of f(h) over the upper hemisphere in (theta, phi).
template <class F>
double hemisphere_integral(F f, int n_theta = 3000, int n_phi = 256) {
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * (0.5 * kPiD) / n_theta;
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPiD / n_phi;
      sum += f(spherical(theta, phi)) * std::sin(theta);
    }
  }
  return sum * (0.5 * kPiD / n_theta) * (2.0 * kPiD / n_phi);
}

TEST(MicrofacetBeckmann, ProjectedDistributionIntegratesToOne) {
  for (const auto& [ax, ay] : {std::pair{0.1f, 0.1f}, {0.4f, 0.4f}, {1.0f, 1.0f}, {0.2f, 0.7f}}) {
    const double total =
        hemisphere_integral([&](const Vec3& h) { return beckmann_d(h, ax, ay) * h.z; });
    EXPECT_NEAR(total, 1.0, 2e-3) << ax << " " << ay;
  }
}

TEST(MicrofacetBeckmann, VisibleNormalDensityIntegratesToOne) {
  for (const auto& [ax, ay] : {std::pair{0.15f, 0.15f}, {0.5f, 0.5f}, {1.0f, 1.0f}, {0.2f, 0.8f}})
    for (const double theta_deg : {0.0, 40.0, 70.0, 85.0}) {
      const Vec3 wo = spherical(theta_deg * kPiD / 180.0, 0.6);
      const double total = hemisphere_integral(
          [&](const Vec3& h) { return beckmann_visible_normal_pdf(wo, h, ax, ay); });
      EXPECT_NEAR(total, 1.0, 3e-3) << ax << " " << ay << " at " << theta_deg;
    }
}

TEST(MicrofacetBeckmann, ValuesAreCyclesFormulas) {
  // Cycles' Beckmann D: exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4), and its G1 from Walter's
  // rational fit: with a = 1 / (alpha tan), 1 above a = 1.6, else
  // (2.181 a^2 + 3.535 a) / (2.577 a^2 + 2.276 a + 1).
  const float alpha = 0.5f;
  const double theta = 0.9;
  const Vec3 w = spherical(theta, 0.3);
  const double tan2 = std::tan(theta) * std::tan(theta), c = std::cos(theta);
  EXPECT_NEAR(beckmann_d(w, alpha, alpha),
              std::exp(-tan2 / (alpha * alpha)) / (kPiD * alpha * alpha * c * c * c * c), 1e-5);
  const double a = 1.0 / (alpha * std::tan(theta));
  const double g1 = (2.181 * a * a + 3.535 * a) / (2.577 * a * a + 2.276 * a + 1.0);
  EXPECT_NEAR(beckmann_g1(w, Vec3(0.0f, 0.0f, 1.0f), alpha, alpha), g1, 1e-6);
  EXPECT_EQ(beckmann_g1(spherical(0.2, 0.0), Vec3(0.0f, 0.0f, 1.0f), alpha, alpha), 1.0f);
  // Anisotropic: the roughness projected onto the azimuth (Heitz 2014, eq. 84).
  const float ax = 0.3f, ay = 0.6f;
  const double phi = 0.3;
  const double alpha_w =
      std::sqrt(std::pow(std::cos(phi) * ax, 2) + std::pow(std::sin(phi) * ay, 2));
  EXPECT_NEAR(beckmann_lambda(w, ax, ay), beckmann_lambda(w, alpha_w, alpha_w), 1e-5);
}

TEST(MicrofacetBeckmann, WaltersApproximationStaysNearTheExactMasking) {
  double worst = 0.0;
  for (int i = 1; i < 400; ++i) {
    const Vec3 w = spherical((i / 400.0) * 0.5 * kPiD * 0.999, 1.1);
    for (const float alpha : {0.05f, 0.3f, 1.0f}) {
      const double exact = 1.0 / (1.0 + beckmann_lambda(w, alpha, alpha));
      const double approx = 1.0 / (1.0 + beckmann_lambda_approx(w, alpha, alpha));
      worst = std::max(worst, std::fabs(approx - exact));
    }
  }
  EXPECT_LT(worst, 4e-3);
  EXPECT_GT(worst, 0.0);  // the two are different functions
}

TEST(MicrofacetBeckmann, SampledNormalsAreVisibleAndAboveTheSurface) {
  uint32_t state = 1;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (1.0f / 16777216.0f);
  };
  for (const double theta_deg : {0.0, 30.0, 60.0, 89.0})
    for (const float alpha : {0.01f, 0.3f, 1.5f}) {
      const Vec3 wo = spherical(theta_deg * kPiD / 180.0, 2.0);
      for (int i = 0; i < 2000; ++i) {
        const Vec3 h = beckmann_sample_visible_normal(wo, alpha, 0.5f * alpha, {next(), next()});
        ASSERT_TRUE(std::isfinite(h.x) && std::isfinite(h.y) && std::isfinite(h.z));
        ASSERT_NEAR(length(h), 1.0f, 1e-5f);
        ASSERT_GT(h.z, 0.0f);
        ASSERT_GE(dot(wo, h), -1e-4f) << theta_deg << " " << alpha;
      }
    }
}

TEST(MicrofacetBeckmann, ErfInverseInvertsErf) {
  // Where float still resolves erf's slope the argument comes back; further out (erf within
  // 1e-4 of 1) erf of the result gives back the value to a float's resolution.
  for (double x = -3.5; x <= 3.5; x += 0.01) {
    const float e = static_cast<float>(std::erf(x));
    if (std::fabs(e) >= 1.0f) continue;
    const float inv = erf_inverse(e);
    if (std::fabs(x) < 2.6) {
      EXPECT_NEAR(inv, x, 2e-4) << x;
    } else {
      EXPECT_NEAR(std::erf(static_cast<double>(inv)), e, 1.2e-7) << x;
    }
  }
  EXPECT_EQ(erf_inverse(0.0f), 0.0f);
  EXPECT_TRUE(std::isfinite(erf_inverse(1.0f)));
  EXPECT_TRUE(std::isfinite(erf_inverse(-1.0f)));
}

}  // namespace
}  // namespace microfacet_beckmann_test
}  // namespace photon

// The BSDF at sampled wavelengths: without dispersion it is the RGB BSDF lane by lane (grey
// colours exactly, others through the uplift), and with dispersion its rough lobes sample the
// mean of the wavelengths' densities and stay unbiased, its smooth refractions follow Snell's law
// with Cauchy's index at the hero wavelength.
#include "photon/render/spectral_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "photon/base/optics.h"
#include "photon/base/sampling.h"
#include "photon/render/bsdf_chi2_util.h"
#include "photon/spectral/dispersion.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {
namespace spectral_bsdf_test {
namespace {

using bsdf_chi2::Uniform;

Vec3 direction(float theta, float phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

Lobe lobe(LobeType type, Vec3 weight, float alpha = 0.0f) {
  Lobe l;
  l.type = type;
  l.weight = weight;
  l.alpha = alpha;
  return l;
}

// Lambert, Schlick GGX, rough glass: every grey.
Bsdf grey_bsdf(bool front = true) {
  Bsdf b(Vec3(0, 0, 1), Vec3(0, 0, 1), front);
  b.add(lobe(LobeType::kLambert, Vec3(0.4f)));
  Lobe spec = lobe(LobeType::kGgxReflection, Vec3(0.7f), 0.09f);
  spec.fresnel = FresnelMode::kSchlick;
  spec.f0 = Vec3(0.04f);
  b.add(spec);
  Lobe glass = lobe(LobeType::kGgxGlass, Vec3(0.5f), 0.16f);
  glass.ior = 1.5f;
  b.add(glass);
  return b;
}

TEST(SpectralBsdf, GreyLobesWithoutDispersionAreTheRgbBsdfAtEveryWavelength) {
  for (bool front : {true, false}) {
    const Bsdf b = grey_bsdf(front);
    const SpectralBsdf sb(b, SampledWavelengths::sample_visible(0.37f));
    Uniform rng(11);
    for (int i = 0; i < 2000; ++i) {
      const Vec3 wo = direction(1.4f * rng.next(), 6.28f * rng.next());
      const Vec3 wi = sample_uniform_sphere(rng.next_2d());
      const Vec3 f = b.eval(wo, wi);
      const SampledSpectrum fs = sb.eval(wo, wi);
      for (int j = 0; j < kSpectrumSamples; ++j) EXPECT_FLOAT_EQ(fs[j], f.x);
      EXPECT_FLOAT_EQ(sb.pdf(wo, wi), b.pdf(wo, wi));
      const float u_lobe = rng.next();
      const Vec2 u = rng.next_2d();
      BsdfSample s;
      SpectralBsdfSample ss;
      const bool ok = b.sample(wo, u_lobe, u, kLobeAll, &s);
      ASSERT_EQ(sb.sample(wo, u_lobe, u, kLobeAll, &ss), ok);
      if (!ok) continue;
      EXPECT_EQ(ss.wi.x, s.wi.x);
      EXPECT_EQ(ss.wi.z, s.wi.z);
      EXPECT_FLOAT_EQ(ss.pdf, s.pdf);
      EXPECT_EQ(ss.flags, s.flags);
      EXPECT_FALSE(ss.terminate);
      for (int j = 0; j < kSpectrumSamples; ++j) EXPECT_FLOAT_EQ(ss.weight[j], s.weight.x);
    }
  }
}

TEST(SpectralBsdf, ColouredWeightsAreTheirUplift) {
  Bsdf b(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
  const Vec3 colour(0.8f, 0.3f, 0.1f);
  b.add(lobe(LobeType::kLambert, colour));
  const auto wl = SampledWavelengths::sample_visible(0.81f);
  const SpectralBsdf sb(b, wl);
  const SampledSpectrum expected = spectral::reflectance_at(colour, wl);
  const SampledSpectrum f = sb.eval(direction(0.3f, 0.0f), direction(0.5f, 2.0f));
  for (int j = 0; j < kSpectrumSamples; ++j) {
    EXPECT_FLOAT_EQ(f[j], expected[j] * kInvPi);
    EXPECT_GE(expected[j], 0.0f);
    EXPECT_LE(expected[j], 1.0f);
  }
  EXPECT_FLOAT_EQ(sb.diffuse_reflectance()[2], expected[2]);
}

Bsdf rough_dispersive_glass(float abbe, bool front) {
  Bsdf b(Vec3(0, 0, 1), Vec3(0, 0, 1), front);
  Lobe glass = lobe(LobeType::kGgxGlass, Vec3(1.0f), 0.04f);
  glass.ior = 1.6f;
  glass.abbe = abbe;
  b.add(glass);
  return b;
}

TEST(SpectralBsdf, RoughDispersiveGlassSamplesTheMeanOfItsWavelengthsDensities) {
  // Wavelengths far apart (uniform rotations): the lanes' refraction lobes separate visibly.
  const auto wl = SampledWavelengths::sample_uniform(0.05f);
  bsdf_chi2::Chi2Test test;
  test.sample_count = 200000;
  const double significance = bsdf_chi2::sidak_significance(2);
  for (bool front : {true, false}) {
    const Bsdf b = rough_dispersive_glass(15.0f, front);
    const SpectralBsdf sb(b, wl);
    const Vec3 wo = direction(0.6f, 0.4f);
    const bsdf_chi2::Chi2Result r = test.run(
        [&](Uniform& rng, Vec3* w) {
          SpectralBsdfSample s;
          const float u_lobe = rng.next();
          if (!sb.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s)) return false;
          *w = s.wi;
          return true;
        },
        [&](const Vec3& w) { return static_cast<double>(sb.pdf(wo, w)); }, 5);
    EXPECT_GT(r.p_value, significance) << "front " << front << " chi2 " << r.statistic;
    EXPECT_EQ(r.outside_support, 0);
  }
}

TEST(SpectralBsdf, RoughDispersiveWeightsEstimateEachWavelengthsAlbedo) {
  const auto wl = SampledWavelengths::sample_uniform(0.05f);
  const Bsdf b = rough_dispersive_glass(15.0f, true);
  const SpectralBsdf sb(b, wl);
  const Vec3 wo = direction(0.7f, 0.0f);
  // Each wavelength's albedo by quadrature of f cos over the sphere.
  for (int j = 0; j < kSpectrumSamples; ++j) {
    const double albedo = bsdf_chi2::Chi2Test::integrate(
        [&](const Vec3& w) { return sb.eval(wo, w)[j] * std::fabs(w.z); }, 0.0, bsdf_chi2::kChi2Pi,
        0.0, 2.0 * bsdf_chi2::kChi2Pi, 1e-5, 0);
    // The same from the sampler's weights.
    Uniform rng(7);
    double sum = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      SpectralBsdfSample s;
      const float u_lobe = rng.next();
      if (sb.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s)) sum += s.weight[j];
    }
    EXPECT_NEAR(sum / n, albedo, 0.01 * albedo) << "lane " << j << " at " << wl.lambda(j) << " nm";
  }
}

TEST(SpectralBsdf, SmoothDispersiveRefractionFollowsTheHeroAndTerminatesTheOthers) {
  const Vec3 wo = direction(0.7f, 0.0f);
  const auto wl = SampledWavelengths::sample_visible(0.63f);
  for (float abbe : {0.0f, 30.0f}) {
    Bsdf b(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
    Lobe refr = lobe(LobeType::kGgxRefraction, Vec3(1.0f));
    refr.ior = 1.5f;
    refr.abbe = abbe;
    b.add(refr);
    const SpectralBsdf sb(b, wl);
    SpectralBsdfSample s;
    ASSERT_TRUE(sb.sample(wo, 0.5f, Vec2(0.5f, 0.5f), kLobeAll, &s));
    const float n = spectral::CauchyDispersion::from_abbe(1.5f, abbe).ior(wl.lambda(0));
    Vec3 expected;
    ASSERT_TRUE(refract(wo, Vec3(0, 0, 1), n, &expected));
    EXPECT_NEAR(s.wi.x, expected.x, 1e-6f);
    EXPECT_NEAR(s.wi.z, expected.z, 1e-6f);
    EXPECT_EQ(s.terminate, abbe > 0.0f);
    EXPECT_FLOAT_EQ(s.weight[0], 1.0f);
    for (int j = 1; j < kSpectrumSamples; ++j) EXPECT_EQ(s.weight[j], abbe > 0.0f ? 0.0f : 1.0f);
  }
  // A single wavelength (a photon's) has nothing to terminate.
  Bsdf b(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
  Lobe refr = lobe(LobeType::kGgxRefraction, Vec3(1.0f));
  refr.abbe = 30.0f;
  b.add(refr);
  SpectralBsdfSample s;
  ASSERT_TRUE(SpectralBsdf(b, SampledWavelengths::single(450.0f, 0.003f))
                  .sample(wo, 0.5f, Vec2(0.5f, 0.5f), kLobeAll, &s));
  EXPECT_FALSE(s.terminate);
}

TEST(SpectralBsdf, SmoothDispersiveReflectionKeepsEveryWavelengthWithItsFresnel) {
  const Vec3 wo = direction(1.2f, 0.0f);
  const auto wl = SampledWavelengths::sample_uniform(0.1f);
  Bsdf b(Vec3(0, 0, 1), Vec3(0, 0, 1), true);
  Lobe glass = lobe(LobeType::kGgxGlass, Vec3(1.0f));
  glass.ior = 1.7f;
  glass.abbe = 12.0f;
  b.add(glass);
  const SpectralBsdf sb(b, wl);
  const spectral::CauchyDispersion cauchy = spectral::CauchyDispersion::from_abbe(1.7f, 12.0f);
  const float f0 = fresnel_dielectric(wo.z, cauchy.ior(wl.lambda(0)));
  SpectralBsdfSample s;
  ASSERT_TRUE(sb.sample(wo, 0.5f * f0, Vec2(0.5f, 0.5f), kLobeAll, &s));  // reflection
  EXPECT_TRUE(s.flags & kLobeReflection);
  EXPECT_FALSE(s.terminate);
  for (int j = 0; j < kSpectrumSamples; ++j)
    EXPECT_NEAR(s.weight[j], fresnel_dielectric(wo.z, cauchy.ior(wl.lambda(j))) / f0, 1e-5f);
  ASSERT_TRUE(sb.sample(wo, 0.5f + 0.5f * f0, Vec2(0.5f, 0.5f), kLobeAll, &s));  // refraction
  EXPECT_TRUE(s.flags & kLobeTransmission);
  EXPECT_TRUE(s.terminate);
}

}  // namespace
}  // namespace spectral_bsdf_test
}  // namespace photon

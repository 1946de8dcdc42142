// The directional albedo of the diffuse lobes (Bsdf::diffuse_reflectance(wo)), which turns the
// photon map's irradiance into reflected radiance, against the integral of the lobes' own eval:
// a closed form that drifted from eval would make photon-mapped images brighter or darker than
// the ray-traced and path-traced ones.
#include <gtest/gtest.h>

#include <cmath>

#include "photon/base/sampling.h"
#include "photon/render/bsdf.h"
#include "photon/render/spectral_bsdf.h"

namespace photon {
namespace diffuse_albedo_test {
namespace {

Bsdf single_lobe(const Lobe& lobe) {
  Bsdf bsdf(Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 0.0f, 1.0f), true);
  bsdf.add(lobe);
  return bsdf;
}

Vec3 view(float cos_o) {
  return {std::sqrt(std::max(0.0f, 1.0f - cos_o * cos_o)), 0.0f, cos_o};
}

// int f(wo, wi) cos_i dwi = pi E[f] over cosine-distributed wi, on a stratified n x n grid.
Vec3 integrated_albedo(const Bsdf& bsdf, const Vec3& wo, int n = 400) {
  Vec3 sum(0.0f);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 wi = sample_cosine_hemisphere(Vec2((i + 0.5f) / n, (j + 0.5f) / n));
      sum += bsdf.eval(wo, wi, kLobeDiffuse);
    }
  return sum * (kPi / (static_cast<float>(n) * n));
}

Lobe lobe_of(LobeType type, float roughness, bool multiscatter = false) {
  Lobe l;
  l.type = type;
  l.weight = Vec3(0.8f, 0.5f, 0.2f);
  l.tint = l.weight;
  l.roughness = roughness;
  l.oren_nayar_multiscatter = multiscatter;
  return l;
}

TEST(DiffuseAlbedo, ClosedFormsMatchTheIntegralOfEvalAtEveryView) {
  const Lobe lobes[] = {
      lobe_of(LobeType::kLambert, 0.0f),         lobe_of(LobeType::kBurleyDiffuse, 0.0f),
      lobe_of(LobeType::kBurleyDiffuse, 0.5f),   lobe_of(LobeType::kBurleyDiffuse, 1.0f),
      lobe_of(LobeType::kOrenNayar, 0.3f),       lobe_of(LobeType::kOrenNayar, 1.0f),
      lobe_of(LobeType::kOrenNayar, 0.6f, true), lobe_of(LobeType::kOrenNayar, 1.0f, true),
  };
  for (const Lobe& lobe : lobes) {
    const Bsdf bsdf = single_lobe(lobe);
    for (const float cos_o : {1.0f, 0.8f, 0.5f, 0.2f, 0.05f}) {
      const Vec3 wo = view(cos_o);
      const Vec3 closed = bsdf.diffuse_reflectance(wo), integral = integrated_albedo(bsdf, wo);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(closed[c], integral[c], 0.004f * integral[c])
            << "lobe type " << static_cast<int>(lobe.type) << " roughness " << lobe.roughness
            << " multiscatter " << lobe.oren_nayar_multiscatter << " cos_o " << cos_o << " channel "
            << c;
    }
  }
}

TEST(DiffuseAlbedo, ABumpedLobeKeepsTheShareItsShadowingTermLeaves) {
  // The shading normal tilted from the smooth (and geometric) one, as a bump map tilts it.
  for (const float tilt_degrees : {10.0f, 30.0f, 50.0f}) {
    const float t = tilt_degrees * kPi / 180.0f;
    for (const LobeType type : {LobeType::kLambert, LobeType::kBurleyDiffuse}) {
      Bsdf bsdf(Vec3(std::sin(t), 0.0f, std::cos(t)), Vec3(0.0f, 0.0f, 1.0f), true);
      bsdf.add(lobe_of(type, 0.5f));
      bsdf.set_smooth_normal(Vec3(0.0f, 0.0f, 1.0f));
      for (const float cos_o : {0.9f, 0.5f}) {
        const Vec3 wo(std::sqrt(1.0f - cos_o * cos_o) * 0.6f,
                      std::sqrt(1.0f - cos_o * cos_o) * 0.8f, cos_o);
        Vec3 sum(0.0f);
        const int n = 400;
        const Frame frame(Vec3(std::sin(t), 0.0f, std::cos(t)));
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            sum += bsdf.eval(
                wo, frame.to_world(sample_cosine_hemisphere(Vec2((i + 0.5f) / n, (j + 0.5f) / n))),
                kLobeDiffuse);
        const float integral = sum.x * kPi / (n * n), closed = bsdf.diffuse_reflectance(wo).x;
        // Exact for Lambert up to the table's interpolation; view and shadowing taken apart for
        // Burley.
        const float tolerance = type == LobeType::kLambert ? 0.005f : 0.04f;
        EXPECT_NEAR(closed, integral, tolerance * integral)
            << "tilt " << tilt_degrees << " type " << static_cast<int>(type) << " cos_o " << cos_o;
        if (type == LobeType::kLambert) EXPECT_LT(closed, 0.8f * 0.99f);
      }
    }
  }
}

TEST(DiffuseAlbedo, BurleyReflectsMoreThanItsColourTowardsGrazingViews) {
  // Cycles' Principled v1 diffuse at roughness 1: about 4% above the colour seen along the
  // normal and half as much again at grazing; at roughness 0 it is darker than Lambert at
  // grazing (F_D90 = 1/2).
  const Bsdf rough = single_lobe(lobe_of(LobeType::kBurleyDiffuse, 1.0f));
  EXPECT_GT(rough.diffuse_reflectance(view(1.0f)).x, 0.8f * 1.02f);
  EXPECT_GT(rough.diffuse_reflectance(view(0.05f)).x, 0.8f * 1.4f);
  const Bsdf smooth = single_lobe(lobe_of(LobeType::kBurleyDiffuse, 0.0f));
  EXPECT_LT(smooth.diffuse_reflectance(view(0.05f)).x, 0.8f * 0.7f);
  // The view-independent colour stays the lobe's weight.
  EXPECT_EQ(rough.diffuse_reflectance().x, 0.8f);
}

TEST(DiffuseAlbedo, SumsOnlyDiffuseLobesAndIsZeroBelowTheSurface) {
  Bsdf bsdf = single_lobe(lobe_of(LobeType::kBurleyDiffuse, 1.0f));
  Lobe glossy;
  glossy.type = LobeType::kGgxReflection;
  glossy.alpha = 0.3f;
  glossy.weight = Vec3(1.0f);
  bsdf.add(glossy);
  bsdf.add(lobe_of(LobeType::kLambert, 0.0f));
  const Vec3 wo = view(0.6f);
  const Vec3 expected =
      single_lobe(lobe_of(LobeType::kBurleyDiffuse, 1.0f)).diffuse_reflectance(wo) +
      Vec3(0.8f, 0.5f, 0.2f);
  EXPECT_NEAR(bsdf.diffuse_reflectance(wo).y, expected.y, 1e-6f);
  EXPECT_EQ(bsdf.diffuse_reflectance(Vec3(0.6f, 0.0f, -0.8f)).x, 0.0f);
}

TEST(DiffuseAlbedo, SpectralMatchesRgbForAGreyLobe) {
  Lobe lobe = lobe_of(LobeType::kBurleyDiffuse, 0.7f);
  lobe.weight = lobe.tint = Vec3(0.6f);
  const Bsdf bsdf = single_lobe(lobe);
  const SampledWavelengths wl = SampledWavelengths::sample_visible(0.37f);
  const SpectralBsdf spectral(bsdf, wl);
  const Vec3 wo = view(0.3f);
  const SampledSpectrum s = spectral.diffuse_reflectance(wo);
  for (int i = 0; i < kSpectrumSamples; ++i)
    EXPECT_NEAR(s[i], bsdf.diffuse_reflectance(wo).x, 2e-3f) << i;
}

}  // namespace
}  // namespace diffuse_albedo_test
}  // namespace photon

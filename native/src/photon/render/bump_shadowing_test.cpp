#include <gtest/gtest.h>

#include <cmath>

#include "photon/render/bsdf.h"

namespace photon {
namespace bump_shadowing_test {
namespace {

Vec3 unit(float x, float y, float z) {
  return normalize(Vec3(x, y, z));
}

Bsdf lambert(const Vec3& ns, const Vec3& ng, LobeType type = LobeType::kLambert) {
  Bsdf bsdf(ns, ng, true);
  Lobe l;
  l.type = type;
  l.weight = Vec3(0.8f);
  bsdf.add(l);
  return bsdf;
}

// Chiang, Li & Burley 2019, eqs. 4-5, written out for the test.
float expected_term(const Vec3& smooth, const Vec3& bumped, const Vec3& wi) {
  const float g = std::fmin(1.0f, dot(smooth, wi) / (dot(bumped, wi) * dot(smooth, bumped)));
  return g < 0.0f ? 0.0f : -g * g * g + g * g + g;
}

TEST(BumpShadowing, DarkensDiffuseLightNearTheSmoothTerminator) {
  // A bump normal tilted towards a grazing light: without the term it would be lit far more
  // brightly than the surface around it (the shadow terminator problem).
  const Vec3 ng(0.0f, 0.0f, 1.0f);
  const Vec3 bumped = unit(0.5f, 0.0f, 1.0f);
  const Vec3 wo = unit(-0.3f, 0.2f, 1.0f), wi = unit(1.0f, 0.0f, 0.15f);
  Bsdf plain = lambert(bumped, ng);
  Bsdf shadowed = lambert(bumped, ng);
  shadowed.set_smooth_normal(ng);
  const float term = expected_term(ng, bumped, wi);
  ASSERT_GT(term, 0.05f);
  ASSERT_LT(term, 0.9f);
  EXPECT_NEAR(plain.eval(wo, wi).x, 0.8f / kPi, 1e-5f);
  EXPECT_NEAR(shadowed.eval(wo, wi).x, 0.8f / kPi * term, 1e-5f);
  // The density is the lobe's own (Cycles scales the value, not the pdf).
  EXPECT_FLOAT_EQ(shadowed.pdf(wo, wi), plain.pdf(wo, wi));
}

TEST(BumpShadowing, LeavesLightFromAboveTheBumpSideAlone) {
  const Vec3 ng(0.0f, 0.0f, 1.0f);
  const Vec3 bumped = unit(0.3f, 0.0f, 1.0f);
  const Vec3 wo = unit(0.0f, 0.3f, 1.0f), wi = unit(-0.4f, 0.1f, 1.0f);  // g >= 1
  Bsdf shadowed = lambert(bumped, ng, LobeType::kBurleyDiffuse);
  Bsdf plain = lambert(bumped, ng, LobeType::kBurleyDiffuse);
  shadowed.set_smooth_normal(ng);
  EXPECT_FLOAT_EQ(expected_term(ng, bumped, wi), 1.0f);
  EXPECT_FLOAT_EQ(shadowed.eval(wo, wi).x, plain.eval(wo, wi).x);
}

TEST(BumpShadowing, SampledWeightsCarryTheTerm) {
  const Vec3 ng(0.0f, 0.0f, 1.0f);
  const Vec3 bumped = unit(0.6f, 0.0f, 1.0f);
  const Vec3 wo = unit(-0.2f, 0.0f, 1.0f);
  Bsdf shadowed = lambert(bumped, ng);
  shadowed.set_smooth_normal(ng);
  int checked = 0;
  for (int i = 0; i < 64; ++i) {
    BsdfSample s;
    if (!shadowed.sample(wo, 0.5f, Vec2((i + 0.5f) / 64.0f, 0.37f), kLobeAll, &s)) continue;
    const float cos_i = std::fabs(dot(bumped, s.wi));
    const float expected = 0.8f / kPi * expected_term(ng, bumped, s.wi) * cos_i / s.pdf;
    EXPECT_NEAR(s.weight.x, expected, 1e-4f);
    ++checked;
  }
  EXPECT_GT(checked, 32);
}

}  // namespace
}  // namespace bump_shadowing_test
}  // namespace photon

// Beckmann microfacet lobes (Glossy, Anisotropic, Glass and Refraction BSDFs with the Beckmann
// distribution; Cycles 4's height-correlated dielectric): they sample what they evaluate
// (chi-square, sample weight = f |cos| / pdf), reflect no more than they receive, and differ from
// GGX at the same roughness where the two distributions do: in the tail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "photon/render/bsdf.h"
#include "photon/render/bsdf_chi2_util.h"

namespace photon {
namespace beckmann_lobes_test {
namespace {

using namespace bsdf_chi2;

const Vec3 kN = normalize(Vec3(-0.2f, 0.4f, 0.85f));

Lobe microfacet(LobeType type, float ax, float ay = -1.0f) {
  Lobe l;
  l.type = type;
  l.alpha = ax;
  l.alpha_y = ay;
  l.ior = 1.45f;
  l.beckmann = true;
  if (ay >= 0.0f) l.tangent = Frame(kN).t;
  return l;
}

Lobe dielectric(float alpha) {
  Lobe l = microfacet(LobeType::kGgxDielectric, alpha);
  l.fresnel = FresnelMode::kSchlickIor;
  l.f0 = Vec3(0.0337f);
  l.correlated = true;
  return l;
}

Bsdf make(const Lobe& l) {
  Bsdf b(kN, kN, true);
  b.add(l);
  return b;
}

Vec3 dir(const Bsdf& b, float theta_deg) {
  return direction_at(b, theta_deg, 0.4f);
}

struct Case {
  std::string name;
  Lobe lobe;
  float theta;
};

std::vector<Case> cases() {
  Lobe correlated = microfacet(LobeType::kGgxReflection, 0.3f);
  correlated.correlated = true;
  return {
      {"Reflection_009_30", microfacet(LobeType::kGgxReflection, 0.09f), 30},
      {"Reflection_05_75", microfacet(LobeType::kGgxReflection, 0.5f), 75},
      {"Reflection_1_50", microfacet(LobeType::kGgxReflection, 1.0f), 50},
      {"Anisotropic_45", microfacet(LobeType::kGgxReflection, 0.3f, 0.05f), 45},
      {"Correlated_60", correlated, 60},
      {"Glass_40", microfacet(LobeType::kGgxGlass, 0.25f), 40},
      {"Refraction_20", microfacet(LobeType::kGgxRefraction, 0.3f), 20},
      {"Dielectric_55", dielectric(0.2f), 55},
  };
}

class BeckmannChi2 : public ::testing::TestWithParam<Case> {};

TEST_P(BeckmannChi2, SampleMatchesPdfAndEval) {
  const Case& c = GetParam();
  const Bsdf b = make(c.lobe);
  const Vec3 wo = dir(b, c.theta);
  Chi2Test test;
  const Chi2Result r = test.run_bsdf(b, wo, std::hash<std::string>()(c.name) & 0xFFFFFFFF);
  EXPECT_EQ(r.outside_support, 0);
  EXPECT_GT(r.dof, 20);
  EXPECT_GT(r.p_value, sidak_significance(static_cast<int>(cases().size())))
      << "chi2 " << r.statistic << " dof " << r.dof;
  std::printf("  %-20s chi2 %8.1f dof %4d p %.3g\n", c.name.c_str(), r.statistic, r.dof, r.p_value);
  int checked = 0;
  EXPECT_TRUE(sample_weights_match(b, wo, 5, 2000, &checked));
  EXPECT_GT(checked, 1000);
}

INSTANTIATE_TEST_SUITE_P(Lobes, BeckmannChi2, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// Directional albedo of a white lobe by quadrature of eval() |cos| over the whole sphere.
double albedo(const Bsdf& b, const Vec3& wo) {
  const int g = 600;
  double sum = 0.0;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      const double z = -1.0 + 2.0 * (i + 0.5) / g, r = std::sqrt(1.0 - z * z);
      const double phi = 2.0 * kChi2Pi * (j + 0.5) / g;
      const Vec3 wi =
          b.frame().to_world(Vec3(static_cast<float>(r * std::cos(phi)),
                                  static_cast<float>(r * std::sin(phi)), static_cast<float>(z)));
      sum += b.eval(wo, wi).x * std::fabs(z);
    }
  return sum * 4.0 * kChi2Pi / (g * g);
}

TEST(BeckmannFurnace, WhiteLobesLoseOnlyWhatMaskingTakes) {
  // Single scattering loses energy to masking and to reflections below the horizon, the more
  // the rougher; it never gains. A smooth lobe keeps nearly all.
  for (const float theta : {0.0f, 45.0f, 75.0f}) {
    const Bsdf smooth = make(microfacet(LobeType::kGgxReflection, 0.05f));
    const Bsdf rough = make(microfacet(LobeType::kGgxReflection, 0.8f));
    const double a_smooth = albedo(smooth, dir(smooth, theta));
    const double a_rough = albedo(rough, dir(rough, theta));
    std::printf("  theta %2.0f: alpha 0.05 %.4f, alpha 0.8 %.4f\n", theta, a_smooth, a_rough);
    EXPECT_LE(a_smooth, 1.005);
    EXPECT_LE(a_rough, a_smooth + 0.005);
    EXPECT_GT(a_rough, 0.6);
    // (The quadrature resolves the smooth lobe to about 2% at the pole.)
    EXPECT_GT(a_smooth, 0.975);
  }
  const Bsdf glass = make(microfacet(LobeType::kGgxGlass, 0.3f));
  const double a_glass = albedo(glass, dir(glass, 30.0f));
  EXPECT_LE(a_glass, 1.005);
  EXPECT_GT(a_glass, 0.9);
}

TEST(BeckmannShape, SameFaceValueAsGgxButAShorterTail) {
  // Both distributions are 1 / (pi alpha^2) at the half vector along the normal, so the mirror
  // direction reflects alike (up to masking); far from it GGX's polynomial tail stays bright
  // where Beckmann's Gaussian fades.
  Lobe beckmann = microfacet(LobeType::kGgxReflection, 0.2f);
  Lobe ggx = beckmann;
  ggx.beckmann = false;
  const Bsdf b = make(beckmann), g = make(ggx);
  const Vec3 wo = b.frame().n;
  EXPECT_NEAR(b.eval(wo, wo).x / g.eval(wo, wo).x, 1.0f, 0.01f);
  const Vec3 off = dir(b, 60.0f);
  EXPECT_LT(b.eval(wo, off).x, 0.05f * g.eval(wo, off).x);
}

}  // namespace
}  // namespace beckmann_lobes_test
}  // namespace photon

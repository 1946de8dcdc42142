#include "photon/render/bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "photon/base/microfacet.h"
#include "photon/base/optics.h"
#include "photon/base/rng.h"
#include "photon/render/bsdf_chi2_util.h"
#include "photon/testing/test_util.h"

namespace photon {
namespace bsdf_test {
namespace {

using namespace bsdf_chi2;

constexpr double kPiD = 3.14159265358979323846;

// ---- Lobe and BSDF construction ----

Lobe lambert(const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kLambert;
  l.weight = w;
  return l;
}

Lobe burley(float roughness, const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kBurleyDiffuse;
  l.weight = w;
  l.roughness = roughness;
  return l;
}

Lobe translucent(const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kTranslucent;
  l.weight = w;
  return l;
}

Lobe ggx(float alpha, FresnelMode mode = FresnelMode::kNone, const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kGgxReflection;
  l.weight = w;
  l.alpha = alpha;
  l.fresnel = mode;
  l.ior = 1.5f;
  l.f0 = Vec3(0.9f, 0.6f, 0.3f);
  return l;
}

Lobe schlick_metal(float alpha, const Vec3& f0) {
  Lobe l = ggx(alpha, FresnelMode::kSchlick);
  l.f0 = f0;
  return l;
}

Lobe glass(float alpha, float ior = 1.5f, const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kGgxGlass;
  l.weight = w;
  l.alpha = alpha;
  l.ior = ior;
  return l;
}

Lobe refraction(float alpha, float ior = 1.5f, const Vec3& w = Vec3(1.0f)) {
  Lobe l = glass(alpha, ior, w);
  l.type = LobeType::kGgxRefraction;
  return l;
}

Lobe transparent(const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kTransparent;
  l.weight = w;
  return l;
}

// A generic (not axis-aligned) shading normal so the frame transforms are exercised.
const Vec3 kNormal = normalize(Vec3(0.3f, -0.2f, 0.9f));

struct BsdfSetup {
  std::vector<Lobe> lobes;
  float theta_o_deg = 45.0f;
  bool front_facing = true;
  float ng_tilt_deg = 0.0f;  // angle between the shading and the geometric normal
};

Bsdf make_bsdf(const BsdfSetup& s) {
  const Frame f(kNormal);
  const float tilt = s.ng_tilt_deg * static_cast<float>(kPiD / 180.0);
  // Tilt ng away from wo's azimuth so wo stays above it.
  const Vec3 ng = normalize(f.to_world(Vec3(-std::sin(tilt), 0.0f, std::cos(tilt))));
  Bsdf b(kNormal, ng, s.front_facing);
  for (const Lobe& l : s.lobes) b.add(l);
  return b;
}

struct Chi2Case {
  std::string name;
  BsdfSetup setup;
};

// Test listings (ctest, --gtest_list_tests) show the case's name instead of its bytes.
void PrintTo(const Chi2Case& c, std::ostream* os) {
  *os << c.name;
}

std::vector<Chi2Case> chi2_cases() {
  std::vector<Chi2Case> c;
  c.push_back({"Lambert_45", {{lambert()}, 45}});
  c.push_back({"Lambert_80", {{lambert()}, 80}});
  c.push_back({"Burley_r05_45", {{burley(0.5f)}, 45}});
  c.push_back({"Translucent_30", {{translucent()}, 30}});
  const float alphas[] = {0.05f, 0.25f, 0.7f};
  const char* alpha_names[] = {"a005", "a025", "a07"};
  const float angles[] = {5.0f, 45.0f, 80.0f};
  for (int a = 0; a < 3; ++a)
    for (float t : angles)
      c.push_back({std::string("Ggx_") + alpha_names[a] + "_" + std::to_string(int(t)),
                   {{ggx(alphas[a])}, t}});
  c.push_back({"GgxSchlick_a025_45", {{schlick_metal(0.25f, Vec3(0.9f, 0.5f, 0.2f))}, 45}});
  c.push_back({"GgxDielectric_a025_60", {{ggx(0.25f, FresnelMode::kDielectric)}, 60}});
  for (int a = 0; a < 3; ++a)
    for (float t : angles)
      c.push_back({std::string("GlassOutside_") + alpha_names[a] + "_" + std::to_string(int(t)),
                   {{glass(alphas[a])}, t}});
  for (int a = 0; a < 3; ++a)
    for (float t : {30.0f, 60.0f})
      c.push_back({std::string("GlassInside_") + alpha_names[a] + "_" + std::to_string(int(t)),
                   {{glass(alphas[a])}, t, false}});
  c.push_back({"RefractionOutside_a025_45", {{refraction(0.25f)}, 45}});
  c.push_back({"RefractionInside_a025_30", {{refraction(0.25f)}, 30, false}});
  c.push_back({"Mixture_45",
               {{lambert(Vec3(0.3f)), schlick_metal(0.2f, Vec3(0.5f)), glass(0.4f, 1.33f)}, 45}});
  c.push_back(
      {"MixtureInside_70",
       {{lambert(Vec3(0.3f)), ggx(0.1f, FresnelMode::kDielectric), glass(0.4f)}, 70, false}});
  // A delta lobe takes part in the lobe choice: the non-delta pdf integrates to less than 1.
  c.push_back({"MixtureWithTransparent_45",
               {{lambert(Vec3(0.5f)), ggx(0.3f), transparent(Vec3(0.4f))}, 45}});
  // Shading normal tilted 15 degrees from the geometric one: directions the geometric normal
  // classifies differently are rejected by both sample() and pdf().
  c.push_back({"ShadingNormal_Lambert_Glass_60",
               {{lambert(Vec3(0.5f)), glass(0.3f), translucent(Vec3(0.2f))}, 60, true, 15}});
  return c;
}

class BsdfChi2 : public ::testing::TestWithParam<Chi2Case> {};

TEST_P(BsdfChi2, SampleMatchesPdf) {
  const Chi2Case& c = GetParam();
  const Bsdf b = make_bsdf(c.setup);
  ASSERT_EQ(b.lobe_count(), static_cast<int>(c.setup.lobes.size()));
  const Vec3 wo = direction_at(b, c.setup.theta_o_deg, 0.7f);
  ASSERT_GT(dot(wo, b.ng()), 0.0f);
  Chi2Test test;
  const Chi2Result r = test.run_bsdf(b, wo, (std::hash<std::string>()(c.name) & 0xFFFFFFFF));
  const double significance = sidak_significance(static_cast<int>(chi2_cases().size()));
  EXPECT_EQ(r.outside_support, 0) << "samples where the pdf integrates to zero";
  EXPECT_GT(r.dof, 20);
  EXPECT_GT(r.observed_total, test.sample_count / 4);
  // The expected counts must account for every returned sample (to the integration accuracy).
  EXPECT_NEAR(r.expected_total / r.observed_total, 1.0, 5e-3);
  EXPECT_GT(r.p_value, significance) << "chi2 " << r.statistic << " dof " << r.dof;
  std::printf("  %-32s chi2 %8.1f dof %4d p %.3g  (samples kept %ld, expected %.0f)\n",
              c.name.c_str(), r.statistic, r.dof, r.p_value, r.observed_total, r.expected_total);
}

INSTANTIATE_TEST_SUITE_P(BsdfLobes, BsdfChi2, ::testing::ValuesIn(chi2_cases()),
                         [](const ::testing::TestParamInfo<Chi2Case>& i) { return i.param.name; });

// The harness must reject wrong pdfs, or the tests above prove nothing.
TEST(BsdfChi2Harness, RejectsAPdfOffByACosine) {
  const Bsdf b = make_bsdf({{ggx(0.25f)}, 45});
  const Vec3 wo = direction_at(b, 45, 0.7f);
  const double significance = sidak_significance(static_cast<int>(chi2_cases().size()));
  // Renormalised, so only the shape is wrong, not the total.
  const Chi2Result r = Chi2Test().run_bsdf(
      b, wo, 7, [](const Vec3& w, double p) { return p * std::fabs(w.z); }, true);
  EXPECT_LT(r.p_value, significance) << "chi2 " << r.statistic << " dof " << r.dof;
}

TEST(BsdfChi2Harness, RejectsAPdfWithAlphaOffByTenPercent) {
  const Bsdf b = make_bsdf({{glass(0.25f)}, 45});
  const Bsdf wrong = make_bsdf({{glass(0.275f)}, 45});
  const Vec3 wo = direction_at(b, 45, 0.7f);
  Chi2Test test;
  const Chi2Result r = test.run(
      [&](Uniform& rng, Vec3* w) {
        BsdfSample s;
        const float u_lobe = rng.next();
        if (!b.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s)) return false;
        *w = b.frame().to_local(s.wi);
        return true;
      },
      [&](const Vec3& w) { return wrong.pdf(wo, wrong.frame().to_world(w)); }, 11);
  EXPECT_LT(r.p_value, sidak_significance(static_cast<int>(chi2_cases().size())))
      << "chi2 " << r.statistic << " dof " << r.dof;
}

TEST(MicrofacetChi2, VisibleNormalSamplingMatchesItsPdf) {
  const double significance = sidak_significance(static_cast<int>(chi2_cases().size()));
  for (float alpha : {0.1f, 0.5f, 1.0f})
    for (float theta : {0.0f, 60.0f, 85.0f}) {
      const float t = theta * static_cast<float>(kPiD / 180.0);
      const Vec3 wo(std::sin(t), 0.0f, std::cos(t));
      Chi2Test test;
      test.sample_count = 200000;
      const Chi2Result r = test.run(
          [&](Uniform& rng, Vec3* h) {
            *h = ggx_sample_visible_normal(wo, alpha, rng.next_2d());
            return true;
          },
          [&](const Vec3& h) { return ggx_visible_normal_pdf(wo, h, alpha); }, 3);
      EXPECT_NEAR(r.expected_total / r.observed_total, 1.0, 5e-3) << alpha << " " << theta;
      EXPECT_EQ(r.outside_support, 0);
      EXPECT_GT(r.p_value, significance)
          << "alpha " << alpha << " theta " << theta << " chi2 " << r.statistic << " dof " << r.dof;
    }
}

// ---- Microfacet identities ----

TEST(Microfacet, DistributionIsNormalisedOverProjectedArea) {
  // Integral of D(h) cos(theta_h) over the hemisphere is 1 (Walter 2007, eq. 4).
  for (float alpha : {0.05f, 0.3f, 1.0f}) {
    const int n = 200000;
    double sum = 0.0;
    // Substitution u = tan^2(theta_h) / (alpha^2 + tan^2): midpoint rule in cos^2.
    for (int i = 0; i < n; ++i) {
      const double c2 = (i + 0.5) / n;  // cos^2(theta)
      const Vec3 h(static_cast<float>(std::sqrt(1.0 - c2)), 0.0f,
                   static_cast<float>(std::sqrt(c2)));
      // d(omega) = 2 pi sin dtheta = pi d(cos^2) / cos.
      sum += ggx_d(h, alpha) * kPiD / n;
    }
    EXPECT_NEAR(sum, 1.0, 2e-3) << alpha;
  }
}

TEST(Microfacet, G1IsOneAtNormalIncidenceAndFallsToZeroAtGrazing) {
  const Vec3 n(0, 0, 1);
  EXPECT_FLOAT_EQ(ggx_g1(n, n, 0.5f), 1.0f);
  const Vec3 grazing = normalize(Vec3(1.0f, 0.0f, 1e-4f));
  EXPECT_LT(ggx_g1(grazing, n, 0.5f), 1e-3f);
  // Walter's eq. 34 closed form at 60 degrees.
  const float t = 60.0f * static_cast<float>(kPiD / 180.0), a = 0.4f;
  const Vec3 w(std::sin(t), 0.0f, std::cos(t));
  const float tan_t = std::tan(t);
  EXPECT_NEAR(ggx_g1(w, n, a), 2.0f / (1.0f + std::sqrt(1.0f + a * a * tan_t * tan_t)), 1e-6f);
  // Back-facing microfacet: chi+ is zero.
  EXPECT_EQ(ggx_g1(w, normalize(Vec3(-1.0f, 0.0f, 0.2f)), a), 0.0f);
}

TEST(Microfacet, SchlickEndpoints) {
  EXPECT_TRUE(VecNear(fresnel_schlick(Vec3(0.04f), 1.0f), Vec3(0.04f), 1e-7f));
  EXPECT_TRUE(VecNear(fresnel_schlick(Vec3(0.04f), 0.0f), Vec3(1.0f), 1e-7f));
}

// ---- Consistency of sample(), eval() and pdf() ----

TEST(BsdfConsistency, SampleWeightAndPdfMatchEvalAndPdf) {
  std::vector<BsdfSetup> setups;
  for (const auto& c : chi2_cases()) setups.push_back(c.setup);
  setups.push_back({{burley(1.0f, Vec3(0.8f, 0.5f, 0.2f)), ggx(0.01f)}, 30});
  Uniform rng(1234);
  int checked = 0;
  for (const BsdfSetup& s : setups) {
    const Bsdf b = make_bsdf(s);
    for (int i = 0; i < 2000; ++i) {
      const float theta = 89.0f * rng.next();
      const Vec3 wo = direction_at(b, theta, 6.2f * rng.next());
      if (dot(wo, b.ng()) <= 0.0f) continue;
      BsdfSample smp;
      const float u_lobe = rng.next();
      if (!b.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &smp)) continue;
      ASSERT_TRUE(is_finite(smp.weight));
      ASSERT_NEAR(length(smp.wi), 1.0f, 1e-4f);
      if (smp.is_delta()) continue;
      const float pdf = b.pdf(wo, smp.wi);
      const Vec3 f = b.eval(wo, smp.wi);
      const float cos_i = std::fabs(dot(smp.wi, b.frame().n));
      ASSERT_GT(pdf, 0.0f);
      EXPECT_NEAR(smp.pdf / pdf, 1.0f, 1e-3f)
          << "setup " << (&s - setups.data()) << " theta_o " << theta << " wi.z "
          << dot(smp.wi, b.frame().n) << " flags " << int(smp.flags);
      const Vec3 expected = f * (cos_i / pdf);
      EXPECT_TRUE(VecNear(smp.weight, expected, 1e-3f * std::max(1.0f, max_component(expected))));
      // The event's side agrees with the geometric normal and the flags.
      const bool reflect = dot(smp.wi, b.ng()) * dot(wo, b.ng()) > 0.0f;
      EXPECT_EQ(reflect, (smp.flags & kLobeReflection) != 0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 30000);
}

TEST(BsdfConsistency, MaskSelectsLobesByFlags) {
  const Bsdf b = make_bsdf({{lambert(Vec3(0.5f)), ggx(0.3f), glass(0.2f)}, 40});
  const Vec3 wo = direction_at(b, 40);
  const Vec3 wi = direction_at(b, 20, 2.0f);
  const Vec3 all = b.eval(wo, wi);
  const Vec3 diffuse = b.eval(wo, wi, kLobeDiffuse);
  const Vec3 glossy = b.eval(wo, wi, kLobeGlossy);
  EXPECT_TRUE(VecNear(diffuse, Vec3(0.5f * kInvPi), 1e-6f));
  EXPECT_TRUE(VecNear(all, diffuse + glossy, 1e-5f));
  EXPECT_TRUE(VecNear(b.diffuse_reflectance(), Vec3(0.5f), 0.0f));
  EXPECT_EQ(b.flags(), kLobeReflection | kLobeTransmission | kLobeDiffuse | kLobeGlossy);
  Uniform rng(5);
  for (int i = 0; i < 1000; ++i) {
    BsdfSample s;
    const float u_lobe = rng.next();
    ASSERT_TRUE(b.sample(wo, u_lobe, rng.next_2d(), kLobeDiffuse, &s));
    EXPECT_EQ(s.flags, kLobeReflection | kLobeDiffuse);
    EXPECT_TRUE(VecNear(s.weight, Vec3(0.5f), 1e-4f));  // Lambert alone: weight = albedo
  }
  BsdfSample s;
  EXPECT_FALSE(b.sample(wo, 0.5f, Vec2(0.5f, 0.5f), kLobeSpecular, &s));
  EXPECT_EQ(b.pdf(wo, wi, kLobeSpecular), 0.0f);
}

// ---- Reciprocity ----

// Not glass: like Cycles 3.4's Glass BSDF it is weighted by the Fresnel of wo (glass_test.cpp).
TEST(BsdfReciprocity, ReflectionLobesAreSymmetric) {
  const std::vector<Lobe> lobes = {lambert(), burley(0.7f), ggx(0.2f),
                                   ggx(0.6f, FresnelMode::kDielectric),
                                   schlick_metal(0.4f, Vec3(0.9f, 0.5f, 0.1f))};
  Uniform rng(99);
  for (const Lobe& l : lobes)
    for (bool front : {true, false}) {
      const Bsdf b = make_bsdf({{l}, 0, front});
      for (int i = 0; i < 500; ++i) {
        const Vec3 wo = direction_at(b, 89.0f * rng.next(), 6.28f * rng.next());
        const Vec3 wi = direction_at(b, 89.0f * rng.next(), 6.28f * rng.next());
        const Vec3 a = b.eval(wo, wi), c = b.eval(wi, wo);
        ASSERT_TRUE(VecNear(a, c, 1e-4f * std::max(1.0f, max_component(a))))
            << "lobe " << static_cast<int>(l.type);
      }
    }
}

// Transmission without the 1/eta^2 radiance scaling: f(wo, wi) n_wo^2 = f(wi, wo) n_wi^2,
// where f(wi, wo) is evaluated by the BSDF seen from wi's side (normals and facing flipped).
// Glass is the refraction lobe weighted by 1 - F(wo.z), which is not symmetric.
TEST(BsdfReciprocity, TransmissionScalesWithTheSquaredIndexRatio) {
  const float ior = 1.5f;
  const std::vector<Lobe> lobes = {refraction(0.15f, ior), refraction(0.6f, ior), translucent()};
  Uniform rng(7);
  for (const Lobe& l : lobes)
    for (bool front : {true, false}) {
      Bsdf b(kNormal, kNormal, front), flipped(-kNormal, -kNormal, !front);
      b.add(l);
      flipped.add(l);
      const bool refractive = l.type != LobeType::kTranslucent;
      // n_wo and n_wi, relative to the outside.
      const float n_wo = front ? 1.0f : ior, n_wi = front ? ior : 1.0f;
      const float scale = refractive ? (n_wo * n_wo) / (n_wi * n_wi) : 1.0f;
      int nonzero = 0;
      for (int i = 0; i < 500; ++i) {
        const Vec3 wo = direction_at(b, 89.0f * rng.next(), 6.28f * rng.next());
        const Vec3 wi = direction_at(flipped, 89.0f * rng.next(), 6.28f * rng.next());
        ASSERT_LT(dot(wi, kNormal), 0.0f);
        const Vec3 forward = b.eval(wo, wi) * scale, backward = flipped.eval(wi, wo);
        ASSERT_TRUE(VecNear(forward, backward, 1e-4f * std::max(1.0f, max_component(backward))))
            << "lobe " << static_cast<int>(l.type) << " front " << front;
        if (max_component(backward) > 0.0f) ++nonzero;
      }
      EXPECT_GT(nonzero, 50);
    }
}

// ---- White furnace: directional albedo by Monte Carlo over sample() weights ----

struct Albedo {
  double mean = 0.0, std_error = 0.0;
};

Albedo directional_albedo(const Bsdf& b, const Vec3& wo, int n, uint64_t seed) {
  Uniform rng(seed);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float u_lobe = rng.next();
    const Vec2 u = rng.next_2d();
    double w = 0.0;
    if (b.sample(wo, u_lobe, u, kLobeAll, &s)) w = s.weight.x;
    sum += w;
    sum2 += w * w;
  }
  Albedo a;
  a.mean = sum / n;
  a.std_error = std::sqrt(std::max(0.0, sum2 / n - a.mean * a.mean) / n);
  return a;
}

void print_albedo(const char* lobe, float alpha, float theta, bool front, const Albedo& a) {
  std::printf("  albedo %-14s alpha %5.3f theta %4.1f %-7s %.4f +- %.4f\n", lobe, alpha, theta,
              front ? "outside" : "inside", a.mean, a.std_error);
}

TEST(BsdfFurnace, LambertIsExactlyOne) {
  const Bsdf b = make_bsdf({{lambert()}, 0});
  for (float theta : {0.0f, 45.0f, 85.0f}) {
    const Vec3 wo = direction_at(b, theta);
    const Albedo a = directional_albedo(b, wo, 20000, 1);
    EXPECT_NEAR(a.mean, 1.0, 5e-3);
    // Independently of sample(): integrate eval() cos over a stratified uniform sphere grid.
    const int n = 400;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
        const double phi = 2.0 * kPiD * (j + 0.5) / n;
        const Vec3 wi =
            b.frame().to_world(Vec3(static_cast<float>(r * std::cos(phi)),
                                    static_cast<float>(r * std::sin(phi)), static_cast<float>(z)));
        sum += b.eval(wo, wi).x * std::fabs(z) * 4.0 * kPiD / (n * n);
      }
    EXPECT_NEAR(sum, 1.0, 5e-3) << theta;
    print_albedo("lambert", 0, theta, true, a);
  }
}

TEST(BsdfFurnace, RoughGlassConservesEnergy) {
  for (float alpha : {0.01f, 0.1f, 0.3f, 0.6f, 1.0f})
    for (bool front : {true, false})
      for (float theta : {0.0f, 45.0f, 80.0f}) {
        const Bsdf b = make_bsdf({{glass(alpha, 1.5f)}, theta, front});
        const Albedo a = directional_albedo(b, direction_at(b, theta), 40000, 17);
        print_albedo("glass", alpha, theta, front, a);
        EXPECT_LE(a.mean, 1.0 + 4.0 * a.std_error + 1e-4);
        // Separable Smith G loses energy at grazing angles and high roughness (no multiple
        // scattering, as in Cycles 3.4's GGX); smooth glass keeps almost all of it.
        if (alpha <= 0.01f) EXPECT_GT(a.mean, 0.99);
        if (alpha <= 0.1f && theta < 60.0f) EXPECT_GT(a.mean, 0.97);
        EXPECT_GT(a.mean, 0.3);
      }
}

TEST(BsdfFurnace, RoughMetalAndGlossyConserveEnergy) {
  for (int metal = 0; metal < 2; ++metal)
    for (float alpha : {0.05f, 0.25f, 0.7f, 1.0f})
      for (float theta : {0.0f, 45.0f, 80.0f}) {
        const Lobe l = metal ? schlick_metal(alpha, Vec3(1.0f)) : ggx(alpha);
        const Bsdf b = make_bsdf({{l}, theta});
        const Albedo a = directional_albedo(b, direction_at(b, theta), 40000, 23);
        print_albedo(metal ? "metal f0=1" : "ggx F=1", alpha, theta, true, a);
        EXPECT_LE(a.mean, 1.0 + 4.0 * a.std_error + 1e-4);
        if (alpha <= 0.05f) EXPECT_GT(a.mean, 0.9);
        EXPECT_GT(a.mean, 0.3);
      }
}

TEST(BsdfFurnace, BurleyDiffuseMatchesItsClosedFormAtNormalIncidence) {
  // At wo = n: FV = 0 and cos_d^2 = (1 + cos_i) / 2, so the albedo is
  // 2 int_0^1 (1 + (F90 - 1)(1 - c)^5) c dc with F90 = 0.5 + roughness (1 + c):
  // 1 - 1/42 for roughness 0 and 1 + 1/42 + 1/84 for roughness 1.
  const Bsdf smooth = make_bsdf({{burley(0.0f)}, 0});
  const Bsdf rough = make_bsdf({{burley(1.0f)}, 0});
  const Albedo a0 = directional_albedo(smooth, smooth.frame().n, 200000, 3);
  const Albedo a1 = directional_albedo(rough, rough.frame().n, 200000, 4);
  print_albedo("burley r=0", 0, 0, true, a0);
  print_albedo("burley r=1", 0, 0, true, a1);
  EXPECT_NEAR(a0.mean, 1.0 - 1.0 / 42.0, 2e-3);
  EXPECT_NEAR(a1.mean, 1.0 + 1.0 / 42.0 + 1.0 / 84.0, 2e-3);
  // Elsewhere: finite, darker at grazing when smooth (Fresnel-like), brighter when rough
  // (retro-reflection), within the range the formula allows for a white base colour.
  for (float roughness : {0.0f, 0.5f, 1.0f})
    for (float theta : {45.0f, 80.0f}) {
      const Bsdf b = make_bsdf({{burley(roughness)}, theta});
      const Albedo a = directional_albedo(b, direction_at(b, theta), 50000, 5);
      print_albedo(
          roughness == 0.0f ? "burley r=0" : (roughness == 1.0f ? "burley r=1" : "burley r=0.5"), 0,
          theta, true, a);
      ASSERT_TRUE(std::isfinite(a.mean));
      if (roughness == 0.0f) EXPECT_LT(a.mean, 1.0 - 1.0 / 42.0);
      if (roughness == 1.0f && theta == 80.0f) EXPECT_GT(a.mean, 1.0 + 1.0 / 28.0);
      EXPECT_GT(a.mean, 0.5);
      EXPECT_LT(a.mean, 1.6);
    }
}

// ---- Delta lobes ----

TEST(BsdfDelta, SharpMirrorReflectsWithFresnelTimesTint) {
  const Vec3 tint(1.0f, 0.5f, 0.25f);
  for (FresnelMode mode : {FresnelMode::kNone, FresnelMode::kDielectric, FresnelMode::kSchlick}) {
    Lobe l = ggx(0.0f, mode, tint);
    const Bsdf b = make_bsdf({{l}, 45});
    EXPECT_EQ(b.flags(), kLobeReflection | kLobeSpecular);
    const Vec3 wo = direction_at(b, 45, 1.0f);
    BsdfSample s;
    ASSERT_TRUE(b.sample(wo, 0.3f, Vec2(0.2f, 0.9f), kLobeAll, &s));
    EXPECT_TRUE(s.is_delta());
    EXPECT_FLOAT_EQ(s.pdf, 1.0f);
    EXPECT_TRUE(VecNear(s.wi, reflect(wo, b.frame().n), 1e-5f));
    const float c = std::cos(static_cast<float>(kPiD / 4));
    Vec3 f(1.0f);
    if (mode == FresnelMode::kDielectric) f = Vec3(fresnel_dielectric(c, 1.5f));
    if (mode == FresnelMode::kSchlick) f = fresnel_schlick(l.f0, c);
    EXPECT_TRUE(VecNear(s.weight, f * tint, 1e-5f));
    // Delta lobes have no density: eval and pdf ignore them.
    EXPECT_TRUE(VecNear(b.eval(wo, s.wi), Vec3(0.0f), 0.0f));
    EXPECT_EQ(b.pdf(wo, s.wi), 0.0f);
  }
}

TEST(BsdfDelta, SharpGlassChoosesReflectionWithProbabilityFresnel) {
  const Vec3 tint(0.9f, 0.8f, 0.7f);
  for (bool front : {true, false})
    for (float theta : {0.0f, 30.0f, 40.0f, 60.0f}) {
      const Bsdf b = make_bsdf({{glass(0.0f, 1.5f, tint)}, theta, front});
      EXPECT_EQ(b.flags(), kLobeReflection | kLobeTransmission | kLobeSpecular);
      const Vec3 wo = direction_at(b, theta);
      const float eta = front ? 1.5f : 1.0f / 1.5f;
      const float fresnel =
          fresnel_dielectric(std::cos(theta * static_cast<float>(kPiD / 180)), eta);
      Uniform rng(31);
      const int n = 100000;
      int reflected = 0;
      for (int i = 0; i < n; ++i) {
        BsdfSample s;
        const float u_lobe = rng.next();
        ASSERT_TRUE(b.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s));
        ASSERT_TRUE(s.is_delta());
        EXPECT_TRUE(VecNear(s.weight, tint, 1e-4f));  // tint F / F or tint (1 - F) / (1 - F)
        const float cos_i = dot(s.wi, b.frame().n);
        if (cos_i > 0.0f) {
          ++reflected;
          EXPECT_NEAR(s.pdf, fresnel, 1e-5f);
          EXPECT_TRUE(VecNear(s.wi, reflect(wo, b.frame().n), 1e-5f));
        } else {
          EXPECT_NEAR(s.pdf, 1.0f - fresnel, 1e-5f);
          // Snell: sin_t = sin_i / eta.
          const float sin_i =
              std::sqrt(std::max(0.0f, 1.0f - dot(wo, b.frame().n) * dot(wo, b.frame().n)));
          const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_i * cos_i));
          EXPECT_NEAR(sin_t, sin_i / eta, 1e-4f);
        }
      }
      const double p = static_cast<double>(reflected) / n;
      const double sigma = std::sqrt(std::max(fresnel * (1.0 - fresnel), 1e-12) / n);
      EXPECT_NEAR(p, fresnel, 4.0 * sigma + 1e-9) << "front " << front << " theta " << theta;
      if (!front && theta >= 60.0f) EXPECT_EQ(reflected, n);  // total internal reflection
    }
}

TEST(BsdfDelta, SharpRefractionRefractsEverythingAndFailsOnTotalInternalReflection) {
  const Bsdf out = make_bsdf({{refraction(0.0f, 1.5f, Vec3(0.5f))}, 30});
  BsdfSample s;
  ASSERT_TRUE(out.sample(direction_at(out, 30), 0.99f, Vec2(0.5f, 0.5f), kLobeAll, &s));
  EXPECT_TRUE(VecNear(s.weight, Vec3(0.5f), 1e-6f));
  EXPECT_LT(dot(s.wi, out.frame().n), 0.0f);
  const Bsdf in = make_bsdf({{refraction(0.0f, 1.5f)}, 60, false});
  EXPECT_FALSE(in.sample(direction_at(in, 60), 0.5f, Vec2(0.5f, 0.5f), kLobeAll, &s));
}

TEST(BsdfDelta, TransparentPassesStraightThrough) {
  const Vec3 tint(0.2f, 0.4f, 0.6f);
  const Bsdf b = make_bsdf({{transparent(tint)}, 50});
  EXPECT_EQ(b.flags(), kLobeTransmission | kLobeSpecular);
  const Vec3 wo = direction_at(b, 50, 2.0f);
  BsdfSample s;
  ASSERT_TRUE(b.sample(wo, 0.7f, Vec2(0.1f, 0.1f), kLobeAll, &s));
  EXPECT_TRUE(VecNear(s.wi, -wo, 1e-6f));
  EXPECT_TRUE(VecNear(s.weight, tint, 1e-6f));
  EXPECT_EQ(s.flags, kLobeTransmission | kLobeSpecular);
}

TEST(BsdfDelta, MixedWithDiffuseTheChoiceProbabilityIsDividedOut) {
  // Lambert 0.5 + transparent 0.5: each chosen half the time; both weights come out as 1.
  const Bsdf b = make_bsdf({{lambert(Vec3(0.5f)), transparent(Vec3(0.5f))}, 30});
  const Vec3 wo = direction_at(b, 30);
  Uniform rng(8);
  int delta = 0;
  for (int i = 0; i < 10000; ++i) {
    BsdfSample s;
    const float u_lobe = rng.next();
    ASSERT_TRUE(b.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s));
    if (s.is_delta()) {
      ++delta;
      EXPECT_NEAR(s.pdf, 0.5f, 1e-6f);
    }
    EXPECT_TRUE(VecNear(s.weight, Vec3(1.0f), 1e-4f));
  }
  EXPECT_NEAR(delta, 5000, 200);
}

// ---- Bad input ----

TEST(BsdfBadInput, NoNanOut) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Bsdf b = make_bsdf(
      {{lambert(), ggx(0.2f, FresnelMode::kDielectric), glass(0.3f), glass(0.0f), translucent()},
       45});
  const Vec3 good = direction_at(b, 45);
  const Vec3 bad[] = {Vec3(nan, 0, 1), Vec3(0.0f), Vec3(inf, 0, 0), -good,
                      normalize(cross(b.frame().n, b.ng()) + b.frame().t)};  // tangent
  for (const Vec3& wo : bad) {
    BsdfSample s;
    EXPECT_FALSE(b.sample(wo, 0.5f, Vec2(0.5f, 0.5f), kLobeAll, &s));
    EXPECT_TRUE(is_finite(b.eval(wo, good)));
    EXPECT_TRUE(is_black(b.eval(wo, good)));
    EXPECT_EQ(b.pdf(wo, good), 0.0f);
    EXPECT_TRUE(is_finite(b.albedo(wo)));
    // Bad wi with a good wo.
    EXPECT_TRUE(is_finite(b.eval(good, wo)));
    EXPECT_TRUE(std::isfinite(b.pdf(good, wo)));
  }
  BsdfSample s;
  EXPECT_FALSE(b.sample(good, nan, Vec2(0.5f, 0.5f), kLobeAll, &s));
  EXPECT_FALSE(b.sample(good, 0.5f, Vec2(nan, 0.5f), kLobeAll, &s));
  // Out-of-range random numbers are clamped, not trusted.
  EXPECT_TRUE(b.sample(good, 1.0f, Vec2(1.0f, 1.0f), kLobeAll, &s));
  EXPECT_TRUE(is_finite(s.weight));

  // Bad normals: the BSDF is black rather than NaN.
  Bsdf no_normal(Vec3(nan, 0, 0), Vec3(0.0f), true);
  no_normal.add(lambert());
  EXPECT_FALSE(no_normal.sample(good, 0.5f, Vec2(0.5f, 0.5f), kLobeAll, &s));
  EXPECT_TRUE(is_black(no_normal.eval(good, -good)));

  // Bad lobe parameters are sanitised.
  Bsdf b2(kNormal, kNormal, true);
  Lobe l = glass(nan, nan, Vec3(nan, 1.0f, -1.0f));
  b2.add(l);
  Lobe m = ggx(inf, FresnelMode::kSchlick);
  m.f0 = Vec3(nan);
  b2.add(m);
  b2.add(lambert(Vec3(-1.0f)));  // black after clamping: dropped
  EXPECT_EQ(b2.lobe_count(), 2);
  Uniform rng(77);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 wo = direction_at(b2, 89.9f * rng.next(), 6.28f * rng.next());
    const float u_lobe = rng.next();
    if (b2.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s)) {
      ASSERT_TRUE(is_finite(s.weight));
      ASSERT_TRUE(std::isfinite(s.pdf));
      ASSERT_TRUE(is_finite(b2.eval(wo, s.wi)));
    }
  }
}

TEST(BsdfBadInput, GrazingAndExtremeParametersStayFinite) {
  Uniform rng(3);
  for (float alpha : {1e-4f, 2e-4f, 1e-3f, 1.0f})
    for (float ior : {1.0f, 1.00001f, 0.5f, 3.0f}) {
      const Bsdf b = make_bsdf({{glass(alpha, ior), refraction(alpha, ior), ggx(alpha)}, 0});
      for (int i = 0; i < 2000; ++i) {
        // Up to 1e-4 radians from the horizon.
        const float theta = 90.0f - std::pow(10.0f, -6.0f * rng.next()) * 10.0f;
        const Vec3 wo = direction_at(b, theta, 6.28f * rng.next());
        BsdfSample s;
        const float u_lobe = rng.next();
        if (!b.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s)) continue;
        ASSERT_TRUE(is_finite(s.weight)) << alpha << " " << ior << " " << theta;
        ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f);
        ASSERT_TRUE(is_finite(b.eval(wo, s.wi)));
        ASSERT_TRUE(std::isfinite(b.pdf(wo, s.wi)));
      }
    }
}

// A material of more closures than the BSDF holds keeps its heaviest lobes, not its first ones:
// nine faint Lambert lobes and then a strong one must keep the strong one.
TEST(BsdfBadInput, FullBsdfKeepsTheHeaviestLobes) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  Bsdf b(n, n, true);
  for (int i = 0; i < Bsdf::kMaxLobes + 1; ++i) b.add(lambert(Vec3(0.01f)));
  b.add(lambert(Vec3(0.5f)));
  ASSERT_EQ(b.lobe_count(), Bsdf::kMaxLobes);
  // Seven faint lobes and the strong one: (7 * 0.01 + 0.5) / pi.
  const Vec3 wo = normalize(Vec3(0.2f, 0.1f, 1.0f)), wi = normalize(Vec3(-0.3f, 0.2f, 1.0f));
  const float expected = (0.01f * (Bsdf::kMaxLobes - 1) + 0.5f) / kPi;
  EXPECT_NEAR(b.eval(wo, wi).x, expected, 1e-5f);
}

}  // namespace
}  // namespace bsdf_test
}  // namespace photon

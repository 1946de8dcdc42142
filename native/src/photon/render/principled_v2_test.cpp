// Principled BSDF v2 (principled_v2.h): the energy tables against their integrals, the F0 / IOR
// level / tint relations, coat absorption, white furnaces, reciprocity of the lobes and chi-square
// tests of sampling against pdf().
#include "photon/render/principled_v2.h"

#include <gtest/gtest.h>

#include <cmath>

#include "photon/base/optics.h"
#include "photon/render/bsdf.h"
#include "photon/render/bsdf_chi2_util.h"
#include "photon/render/bsdf_lobes.h"
#include "photon/render/microfacet_albedo.h"
#include "photon/render/microfacet_albedo_integrals.h"

namespace photon {
namespace principled_v2_test {
namespace {

using bsdf_chi2::Uniform;
namespace ma = microfacet_albedo;

Vec3 direction(float cos_theta, float phi = 0.0f) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

const Vec3 kN(0.0f, 0.0f, 1.0f);

// A Bsdf holding one Principled v2 closure of weight 1 seen from wo (front side unless told).
Bsdf principled(const PrincipledV2Inputs& in, const Vec3& wo, bool front = true,
                Vec3* emission = nullptr) {
  Bsdf b(kN, kN, front);
  PrincipledV2Geometry g;
  g.wo = wo;
  g.n = kN;
  g.coat_n = kN;
  g.tangent = Vec3(1.0f, 0.0f, 0.0f);
  g.front = front;
  const Vec3 e = add_principled_v2(in, 1.0f, g, &b);
  if (emission) *emission = e;
  return b;
}

// Directional albedo at wo by sampling (every lobe, reflection and transmission, delta ones too).
Vec3 albedo(const Bsdf& b, const Vec3& wo, int n = 400000, uint64_t seed = 7) {
  Uniform rng(seed);
  Vec3 sum(0.0f);
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float u = rng.next();
    if (b.sample(wo, u, rng.next_2d(), kLobeAll, &s)) sum += s.weight;
  }
  return sum / static_cast<float>(n);
}

// ---- The tables ----

TEST(MicrofacetAlbedo, TablesHoldTheirIntegrals) {
  using ma::Quantity;
  struct Case {
    Quantity q;
    int x, y, z;
    bool inverted;
  };
  const Case cases[] = {
      {Quantity::kReflection, 8, 20, 0, false}, {Quantity::kReflection, 31, 31, 0, false},
      {Quantity::kReflection, 20, 3, 0, false}, {Quantity::kGlass, 5, 9, 4, false},
      {Quantity::kGlass, 15, 15, 10, false},    {Quantity::kGlass, 7, 4, 6, true},
      {Quantity::kSchlickIor, 9, 7, 5, false},  {Quantity::kSchlickIor, 3, 12, 12, false},
  };
  for (const Case& c : cases) {
    const int size = c.q == Quantity::kReflection ? ma::kReflectionSize : ma::kGlassSize;
    const float ior = c.q == Quantity::kReflection ? 1.0f : ma::grid_ior(c.z, size);
    // A finer grid than the generator's: the committed values are the integrals to ~3e-3.
    const double fresh =
        ma::directional(c.q, ma::grid_roughness(c.x, size), ma::grid_cosine(c.y, size),
                        c.inverted ? 1.0f / ior : ior, 160);
    const int i = (c.z * size + c.y) * size + c.x;
    const float* table = c.q == Quantity::kReflection ? ma::kReflectionE
                         : c.q == Quantity::kSchlickIor
                             ? ma::kSchlickIorS
                             : (c.inverted ? ma::kGlassInvE : ma::kGlassE);
    EXPECT_NEAR(table[i], fresh, 5e-3)
        << static_cast<int>(c.q) << " " << c.x << " " << c.y << " " << c.z;
  }
  // Lookups at grid points return the entries; E of a smooth surface is 1.
  EXPECT_FLOAT_EQ(ma::reflection_albedo(1.0f, 1.0f), ma::kReflectionE[32 * 32 - 1]);
  EXPECT_FLOAT_EQ(ma::reflection_albedo(0.0f, 0.5f), 1.0f);
  // Rough GGX loses energy: at r = 1, head-on, about two thirds of it.
  EXPECT_LT(ma::reflection_albedo(1.0f, 1.0f), 0.4f);
  EXPECT_GT(ma::reflection_albedo_average(0.5f), 0.85f);
}

TEST(MicrofacetAlbedo, ReflectionAlbedoMatchesTheLobe) {
  // The table's E against a furnace of the correlated single-scattering GGX lobe it describes.
  for (float r : {0.3f, 0.7f, 1.0f})
    for (float mu : {0.2f, 0.6f, 1.0f}) {
      Bsdf b(kN, kN, true);
      Lobe l;
      l.type = LobeType::kGgxReflection;
      l.alpha = r * r;
      l.correlated = true;
      b.add(l);
      const Vec3 wo = direction(mu);
      EXPECT_NEAR(albedo(b, wo, 200000).x, ma::reflection_albedo(r, mu), 0.01) << r << " " << mu;
    }
}

// ---- F0, IOR level, tints ----

TEST(PrincipledV2, SpecularIorLevelScalesF0ThroughTheIor) {
  using principled_v2::specular_eta;
  EXPECT_EQ(specular_eta(1.5f, 0.5f), 1.5f);        // the IOR's own F0 = 0.04
  EXPECT_FLOAT_EQ(specular_eta(1.5f, 0.0f), 1.0f);  // no specular at all
  const float eta1 = specular_eta(1.5f, 1.0f);
  EXPECT_NEAR(ma::f0_from_ior(eta1), 0.08f, 1e-6f);  // twice F0
  const float eta_q = specular_eta(1.5f, 0.25f);
  EXPECT_NEAR(ma::f0_from_ior(eta_q), 0.02f, 1e-6f);
  EXPECT_LT(specular_eta(0.8f, 1.0f), 1.0f);  // an IOR below 1 stays below 1

  // Smooth dielectric: head-on it reflects F0 x Specular Tint, at grazing white.
  PrincipledV2Inputs in;
  in.roughness = 0.0f;
  in.base_color = Vec3(0.0f);
  in.specular_tint = Vec3(1.0f, 0.5f, 0.25f);
  for (float level : {0.0f, 0.5f, 1.0f}) {
    in.specular_ior_level = level;
    const Vec3 wo = direction(1.0f);
    const Bsdf b = principled(in, wo);
    Vec3 reflected(0.0f);
    for (int i = 0; i < b.lobe_count(); ++i)
      if (b.lobe(i).type == LobeType::kGgxReflection)
        reflected += b.lobe(i).weight * lobe_reflection_fresnel(b.lobe(i), 1.0f, b.lobe(i).ior);
    const Vec3 expect = in.specular_tint * (0.04f * 2.0f * level);
    EXPECT_NEAR(reflected.x, expect.x, 1e-4f) << level;
    EXPECT_NEAR(reflected.y, expect.y, 1e-4f) << level;
    EXPECT_NEAR(reflected.z, expect.z, 1e-4f) << level;
  }
  in.specular_ior_level = 0.5f;
  const Bsdf b = principled(in, direction(1.0f));
  ASSERT_GE(b.lobe_count(), 1);
  const Lobe& s = b.lobe(0);
  ASSERT_EQ(s.fresnel, FresnelMode::kSchlickIor);
  const Vec3 edge = lobe_reflection_fresnel(s, 1e-4f, s.ior);
  EXPECT_NEAR(edge.z, 1.0f, 1e-3f);  // edges stay white
}

TEST(PrincipledV2, F82TintIsF0HeadOnAndTintedSchlickAt82Degrees) {
  const Vec3 f0(0.9f, 0.6f, 0.3f), tint(0.5f, 1.0f, 0.2f);
  Lobe l;
  l.type = LobeType::kGgxReflection;
  l.fresnel = FresnelMode::kF82Tint;
  l.f0 = f0;
  l.tint = tint;
  const Vec3 head_on = lobe_reflection_fresnel(l, 1.0f, 1.0f);
  EXPECT_NEAR(head_on.x, f0.x, 1e-6f);
  EXPECT_NEAR(head_on.z, f0.z, 1e-6f);
  const float c = 1.0f / 7.0f;
  const Vec3 at82 = lobe_reflection_fresnel(l, c, 1.0f);
  const Vec3 schlick = fresnel_schlick(f0, c);
  EXPECT_NEAR(at82.x, schlick.x * tint.x, 1e-5f);
  EXPECT_NEAR(at82.y, schlick.y * tint.y, 1e-5f);
  EXPECT_NEAR(at82.z, schlick.z * tint.z, 1e-5f);
  // Clamped to [0, 1] everywhere.
  for (float cc = 0.0f; cc <= 1.0f; cc += 0.01f) {
    const Vec3 f = lobe_reflection_fresnel(l, cc, 1.0f);
    EXPECT_GE(f.x, 0.0f);
    EXPECT_LE(f.y, 1.0f);
  }
}

TEST(PrincipledV2, CoatTintAbsorbsAlongTheRefractedPath) {
  PrincipledV2Inputs in;
  in.base_color = Vec3(1.0f);
  in.specular_ior_level = 0.0f;  // only the coat and the diffuse
  in.coat_weight = 1.0f;
  in.coat_ior = 1.5f;
  in.coat_tint = Vec3(0.5f, 0.8f, 1.0f);
  for (float mu : {1.0f, 0.5f, 0.2f}) {
    const Bsdf b = principled(in, direction(mu));
    const Lobe* diffuse = nullptr;
    for (int i = 0; i < b.lobe_count(); ++i)
      if (b.lobe(i).type == LobeType::kLambert) diffuse = &b.lobe(i);
    ASSERT_NE(diffuse, nullptr);
    const float f = fresnel_dielectric(mu, 1.5f);
    const float cos_t = std::sqrt(1.0f - (1.0f - mu * mu) / (1.5f * 1.5f));
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(diffuse->weight[c], (1.0f - f) * std::pow(in.coat_tint[c], 1.0f / cos_t), 1e-5f)
          << mu << " " << c;
  }
  // Half a coat: half the absorption (mix(1, tint^d, weight)).
  in.coat_weight = 0.5f;
  const Bsdf b = principled(in, direction(1.0f));
  const float f = fresnel_dielectric(1.0f, 1.5f);
  EXPECT_NEAR(b.lobe(b.lobe_count() - 1).weight.x, (1.0f - 0.5f * f) * 0.75f, 1e-5f);
}

TEST(PrincipledV2, EmissionIsUnderTheCoat) {
  PrincipledV2Inputs in;
  in.emission = Vec3(1.0f, 0.5f, 0.25f);
  in.emission_strength = 2.0f;
  Vec3 e;
  principled(in, direction(1.0f), true, &e);
  EXPECT_NEAR(e.y, 1.0f, 1e-6f);
  in.coat_weight = 1.0f;
  principled(in, direction(1.0f), true, &e);
  EXPECT_NEAR(e.y, 1.0f - fresnel_dielectric(1.0f, 1.5f), 1e-6f);
  // Default v2 emission: white colour, strength 0: nothing.
  principled(PrincipledV2Inputs{}, direction(1.0f), true, &e);
  EXPECT_EQ(max_component(e), 0.0f);
}

// ---- Energy ----

TEST(PrincipledV2, WhiteFurnaceConservesEnergyWithMultiscatter) {
  struct Case {
    const char* name;
    PrincipledV2Inputs in;
    float lo, hi;
  };
  std::vector<Case> cases;
  PrincipledV2Inputs white;
  white.base_color = Vec3(1.0f);
  for (float r : {0.2f, 0.5f, 1.0f}) {
    PrincipledV2Inputs d = white;
    d.roughness = r;
    cases.push_back({"dielectric", d, 0.97f, 1.005f});  // Cycles' is ~1 (albedo-scaled layers)
    PrincipledV2Inputs m = d;
    m.metallic = 1.0f;
    cases.push_back({"metal", m, 0.97f, 1.005f});
    PrincipledV2Inputs g = d;
    g.transmission = 1.0f;
    cases.push_back({"glass", g, 0.95f, 1.01f});
    PrincipledV2Inputs c = d;
    c.coat_weight = 1.0f;
    cases.push_back({"coated", c, 0.9f, 1.005f});
  }
  for (const Case& c : cases)
    for (float mu : {0.3f, 0.8f}) {
      const Vec3 wo = direction(mu, 0.3f);
      const Vec3 a = albedo(principled(c.in, wo), wo, 200000);
      EXPECT_GE(a.x, c.lo) << c.name << " r " << c.in.roughness << " mu " << mu;
      EXPECT_LE(a.x, c.hi) << c.name << " r " << c.in.roughness << " mu " << mu;
    }
  // Without Multiscatter GGX a rough metal loses what single scattering cannot reflect.
  PrincipledV2Inputs m = white;
  m.metallic = 1.0f;
  m.roughness = 1.0f;
  m.multiscatter = false;
  const Vec3 wo = direction(0.8f);
  EXPECT_LT(albedo(principled(m, wo), wo, 200000).x, 0.75f);
}

// ---- Reciprocity of the lobes (the layer weights depend on wo, as in Cycles) ----

TEST(PrincipledV2, DiffuseRoughnessIsEnergyPreservingOrenNayar) {
  PrincipledV2Inputs in;
  in.base_color = Vec3(0.7f, 0.4f, 1.3f);
  in.specular_ior_level = 0.0f;
  for (float r : {0.0f, 0.6f}) {
    in.diffuse_roughness = r;
    const Bsdf b = principled(in, direction(0.8f));
    const Lobe* diffuse = nullptr;
    for (int i = 0; i < b.lobe_count(); ++i)
      if (b.lobe(i).type == LobeType::kLambert || b.lobe(i).type == LobeType::kOrenNayar)
        diffuse = &b.lobe(i);
    ASSERT_NE(diffuse, nullptr);
    EXPECT_EQ(diffuse->type, r > 0.0f ? LobeType::kOrenNayar : LobeType::kLambert);
    if (r == 0.0f) continue;
    EXPECT_NEAR(diffuse->roughness, r, 1e-7f);
    EXPECT_TRUE(diffuse->oren_nayar_multiscatter);
    EXPECT_NEAR(diffuse->tint.z, 1.0f, 1e-7f);  // the albedo clamped to [0, 1]
    EXPECT_NEAR(diffuse->tint.y, 0.4f, 1e-7f);
  }
}

TEST(PrincipledV2, LobesAreReciprocal) {
  std::vector<Lobe> lobes;
  Lobe f82;
  f82.type = LobeType::kGgxReflection;
  f82.fresnel = FresnelMode::kF82Tint;
  f82.f0 = Vec3(0.9f, 0.5f, 0.2f);
  f82.tint = Vec3(0.3f, 0.9f, 1.0f);
  f82.alpha = 0.3f;
  f82.correlated = true;
  lobes.push_back(f82);
  Lobe spec = f82;
  spec.fresnel = FresnelMode::kSchlickIor;
  spec.ior = 1.7f;
  spec.fixed_ior = true;
  spec.f0 = Vec3(0.06f, 0.03f, 0.01f);
  lobes.push_back(spec);
  Lobe aniso = f82;
  aniso.alpha_y = 0.05f;
  aniso.tangent = Vec3(1.0f, 1.0f, 0.0f);
  lobes.push_back(aniso);
  Uniform rng(3);
  for (const Lobe& l : lobes) {
    Bsdf b(kN, kN, true);
    b.add(l);
    for (int i = 0; i < 200; ++i) {
      const Vec3 a = direction(0.05f + 0.95f * rng.next(), 6.28f * rng.next());
      const Vec3 c = direction(0.05f + 0.95f * rng.next(), 6.28f * rng.next());
      const Vec3 f1 = b.eval(a, c), f2 = b.eval(c, a);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(f1[k], f2[k], 1e-4f * (1.0f + f1[k]));
    }
  }
  // The dielectric interface: f(wo, wi) / eta_i^2 is symmetric for refraction (Veach 1997,
  // eq. 5.14, without the radiance scaling Photon and Cycles leave out: f_t(o, i) eta_o^2 =
  // f_t(i, o) eta_i^2 with eta the relative index on each side).
  Lobe d;
  d.type = LobeType::kGgxDielectric;
  d.fresnel = FresnelMode::kSchlickIor;
  d.ior = 1.5f;
  d.f0 = Vec3(ma::f0_from_ior(1.5f));
  d.alpha = 0.2f;
  d.correlated = true;
  Bsdf outside(kN, kN, true), inside(kN, kN, false);
  outside.add(d);
  inside.add(d);
  for (int i = 0; i < 200; ++i) {
    const Vec3 a = direction(0.05f + 0.95f * rng.next(), 6.28f * rng.next());
    Vec3 c = direction(0.05f + 0.95f * rng.next(), 6.28f * rng.next());
    c.z = -c.z;
    const float f_out = outside.eval(a, c).x;  // from outside (eta 1.5) into the glass
    // The same pair from inside: wo = -c in the inside BSDF's frame (normal flipped to -c's side).
    Bsdf flipped(-kN, -kN, false);
    flipped.add(d);
    const float f_in = flipped.eval(c, a).x;
    EXPECT_NEAR(f_out, f_in * 1.5f * 1.5f, 1e-3f * (1.0f + f_out)) << i;
  }
}

// ---- Sampling against pdf() ----

TEST(PrincipledV2, SamplingMatchesPdf) {
  bsdf_chi2::Chi2Test test;
  test.sample_count = 200000;
  std::vector<std::pair<const char*, PrincipledV2Inputs>> cases;
  PrincipledV2Inputs base;
  base.base_color = Vec3(0.7f, 0.5f, 0.3f);
  base.roughness = 0.4f;
  cases.push_back({"dielectric", base});
  PrincipledV2Inputs metal = base;
  metal.metallic = 0.7f;
  metal.specular_tint = Vec3(0.5f, 0.9f, 1.0f);
  metal.anisotropic = 0.6f;
  metal.anisotropic_rotation = 0.1f;
  cases.push_back({"metal", metal});
  PrincipledV2Inputs glass = base;
  glass.transmission = 1.0f;
  glass.roughness = 0.3f;
  cases.push_back({"glass", glass});
  PrincipledV2Inputs coated = metal;
  coated.transmission = 0.5f;
  coated.coat_weight = 0.8f;
  coated.coat_roughness = 0.2f;
  coated.coat_tint = Vec3(0.8f, 0.6f, 0.9f);
  cases.push_back({"everything", coated});
  const double significance = bsdf_chi2::sidak_significance(static_cast<int>(cases.size()) * 4);
  uint64_t seed = 11;
  for (const auto& [name, in] : cases)
    for (bool front : {true, false})
      for (float mu : {0.9f, 0.35f}) {
        const Vec3 wo = direction(mu, 0.7f);
        const Bsdf b = principled(in, wo, front);
        const bsdf_chi2::Chi2Result r = test.run_bsdf(b, wo, seed++);
        EXPECT_GT(r.p_value, significance) << name << (front ? " front" : " back") << " mu " << mu
                                           << " chi2 " << r.statistic << " dof " << r.dof;
        EXPECT_EQ(r.outside_support, 0) << name;
      }
}

}  // namespace
}  // namespace principled_v2_test
}  // namespace photon

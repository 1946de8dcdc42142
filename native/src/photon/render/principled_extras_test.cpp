// The Principled BSDF's sheen, anisotropic specular, transmission roughness, clearcoat normal
// and subsurface fallback, the Diffuse BSDF's Oren-Nayar roughness and the Velvet BSDF: their
// lobes sample what
// they evaluate (chi-square), conserve energy (white furnace) and take the shapes Cycles 3.4
// gives them; and material_eval builds them from the inputs as Cycles' Principled v1 does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "photon/base/microfacet.h"
#include "photon/base/optics.h"
#include "photon/render/bsdf.h"
#include "photon/render/bsdf_chi2_util.h"
#include "photon/render/bsdf_lobes.h"
#include "photon/render/material_eval.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace principled_extras_test {
namespace {

using namespace bsdf_chi2;

const Vec3 kN = normalize(Vec3(0.3f, -0.2f, 0.9f));

Lobe oren_nayar(float sigma) {
  Lobe l;
  l.type = LobeType::kOrenNayar;
  l.roughness = sigma;
  return l;
}

// Cycles 4.3's Oren-Nayar: multiple scattering of albedo `albedo` put back.
Lobe oren_nayar_ms(float sigma, const Vec3& albedo) {
  Lobe l = oren_nayar(sigma);
  l.oren_nayar_multiscatter = true;
  l.tint = albedo;
  return l;
}

Lobe sheen(const Vec3& w = Vec3(1.0f)) {
  Lobe l;
  l.type = LobeType::kSheen;
  l.weight = w;
  return l;
}

Lobe velvet(float sigma) {
  Lobe l;
  l.type = LobeType::kVelvet;
  l.roughness = sigma;
  return l;
}

Lobe aniso_ggx(float ax, float ay, const Vec3& tangent) {
  Lobe l;
  l.type = LobeType::kGgxReflection;
  l.alpha = ax;
  l.alpha_y = ay;
  l.tangent = tangent;
  return l;
}

Lobe lambert(const Vec3& w) {
  Lobe l;
  l.type = LobeType::kLambert;
  l.weight = w;
  return l;
}

// A tangent in kN's plane at `deg` degrees from its frame's t.
Vec3 tangent_at(float deg) {
  const Frame f(kN);
  const float a = deg * static_cast<float>(kChi2Pi / 180.0);
  return f.t * std::cos(a) + f.b * std::sin(a);
}

Bsdf make(const std::vector<Lobe>& lobes, const Vec3& n = kN) {
  Bsdf b(n, n, true);
  for (const Lobe& l : lobes) b.add(l);
  return b;
}

Vec3 dir(const Bsdf& b, float theta_deg, float phi = 0.7f) {
  return direction_at(b, theta_deg, phi);
}

struct Case {
  std::string name;
  std::vector<Lobe> lobes;
  float theta;
};

std::vector<Case> cases() {
  Lobe coat;  // a clearcoat on a normal tilted 20 degrees from the shading normal
  coat.type = LobeType::kGgxReflection;
  coat.alpha = 0.09f;
  coat.fresnel = FresnelMode::kSchlick;
  coat.normal = Frame(kN).to_world(Vec3(std::sin(0.35f), 0.0f, std::cos(0.35f)));
  Lobe refl;  // the Principled glass split: reflection with roughness 0.3, refraction 0.72
  refl.type = LobeType::kGgxReflection;
  refl.alpha = 0.09f;
  refl.weight = Vec3(0.1f);
  Lobe refr;
  refr.type = LobeType::kGgxRefraction;
  refr.alpha = 0.52f;
  refr.ior = 1.45f;
  refr.weight = Vec3(0.9f);
  return {
      {"OrenNayar_45", {oren_nayar(0.5f)}, 45},
      {"OrenNayar_80", {oren_nayar(1.0f)}, 80},
      {"OrenNayarMultiscatter_60", {oren_nayar_ms(0.8f, Vec3(0.9f, 0.5f, 0.2f))}, 60},
      {"Sheen_30", {sheen()}, 30},
      {"Sheen_80", {sheen()}, 80},
      {"SheenOnBurley_60", {lambert(Vec3(0.5f)), sheen(Vec3(0.7f))}, 60},
      {"Velvet_30", {velvet(0.5f)}, 30},
      {"Velvet_80", {velvet(1.0f)}, 80},
      {"AnisoGgx_45", {aniso_ggx(0.3f, 0.05f, tangent_at(40))}, 45},
      {"AnisoGgxWide_70", {aniso_ggx(1.0f, 0.1f, tangent_at(-25))}, 70},
      {"ClearcoatNormal_50", {lambert(Vec3(0.5f)), coat}, 50},
      {"GlassSplit_40", {refl, refr}, 40},
  };
}

class PrincipledExtrasChi2 : public ::testing::TestWithParam<Case> {};

TEST_P(PrincipledExtrasChi2, SampleMatchesPdfAndEval) {
  const Case& c = GetParam();
  const Bsdf b = make(c.lobes);
  ASSERT_EQ(b.lobe_count(), static_cast<int>(c.lobes.size()));
  const Vec3 wo = dir(b, c.theta);
  Chi2Test test;
  const Chi2Result r = test.run_bsdf(b, wo, std::hash<std::string>()(c.name) & 0xFFFFFFFF);
  EXPECT_EQ(r.outside_support, 0);
  EXPECT_GT(r.dof, 20);
  EXPECT_NEAR(r.expected_total / r.observed_total, 1.0, 5e-3);
  EXPECT_GT(r.p_value, sidak_significance(static_cast<int>(cases().size())))
      << "chi2 " << r.statistic << " dof " << r.dof;
  std::printf("  %-22s chi2 %8.1f dof %4d p %.3g\n", c.name.c_str(), r.statistic, r.dof, r.p_value);
  // The sample weight is eval |cos| / pdf of what eval() and pdf() say for that direction.
  EXPECT_TRUE(sample_weights_match(b, wo, 7, 2000));
}

INSTANTIATE_TEST_SUITE_P(Lobes, PrincipledExtrasChi2, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// Directional albedo by sample() and, independently, by quadrature of eval() cos.
struct Albedos {
  double sampled = 0.0, sampled_error = 0.0, integrated = 0.0;
};

Albedos albedos(const Bsdf& b, const Vec3& wo) {
  Albedos a;
  Uniform rng(11);
  const int n = 40000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float ul = rng.next();
    const double w = b.sample(wo, ul, rng.next_2d(), kLobeAll, &s) ? s.weight.x : 0.0;
    sum += w;
    sum2 += w * w;
  }
  a.sampled = sum / n;
  a.sampled_error = std::sqrt(std::max(0.0, sum2 / n - a.sampled * a.sampled) / n);
  const int g = 500;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      const double z = (i + 0.5) / g, r = std::sqrt(1.0 - z * z);
      const double phi = 2.0 * kChi2Pi * (j + 0.5) / g;
      const Vec3 wi =
          b.frame().to_world(Vec3(static_cast<float>(r * std::cos(phi)),
                                  static_cast<float>(r * std::sin(phi)), static_cast<float>(z)));
      a.integrated += b.eval(wo, wi).x * z * 2.0 * kChi2Pi / (g * g);
    }
  return a;
}

TEST(PrincipledExtrasFurnace, OrenNayarSheenVelvetAndAnisotropicGgxConserveEnergy) {
  const std::vector<std::pair<const char*, Lobe>> lobes = {
      {"oren-nayar 0", oren_nayar(0.0f)},
      {"oren-nayar 1", oren_nayar(1.0f)},
      {"sheen", sheen()},
      {"velvet 0.2", velvet(0.2f)},
      {"velvet 1", velvet(1.0f)},
      {"aniso 0.5/0.02", aniso_ggx(0.5f, 0.02f, tangent_at(30))},
      {"aniso 1/0.32", aniso_ggx(1.0f, 0.316f, tangent_at(-60))},
  };
  for (const auto& [name, lobe] : lobes)
    for (float theta : {0.0f, 45.0f, 80.0f}) {
      const Bsdf b = make({lobe});
      const Albedos a = albedos(b, dir(b, theta));
      std::printf("  albedo %-16s theta %4.1f sampled %.4f +- %.4f integrated %.4f\n", name, theta,
                  a.sampled, a.sampled_error, a.integrated);
      EXPECT_NEAR(a.sampled, a.integrated, 4.0 * a.sampled_error + 2e-3) << name << " " << theta;
      EXPECT_LE(a.integrated, 1.0 + 2e-3) << name << " " << theta;
      EXPECT_GT(a.integrated, 0.0) << name << " " << theta;
    }
  // Oren-Nayar at sigma 0 is Lambert; at normal incidence the qualitative model's A term alone
  // remains: pi A = pi / (pi + (3 pi - 4) / 6 sigma).
  const Bsdf on0 = make({oren_nayar(0.0f)});
  EXPECT_NEAR(albedos(on0, dir(on0, 45)).integrated, 1.0, 2e-3);
  const Bsdf on1 = make({oren_nayar(1.0f)});
  const double expected = kChi2Pi / (kChi2Pi + (3.0 * kChi2Pi - 4.0) / 6.0);
  EXPECT_NEAR(albedos(on1, on1.frame().n).integrated, expected, 2e-3);
}

TEST(PrincipledExtrasVelvet, CyclesAshikhminVelvet) {
  const Bsdf b = make({velvet(1.0f)});
  // Retro-reflection at 60 degrees, Sigma 1: h = wo, cos_h = 1/2, G = min(1, 2 (1/2) (1/2)) = 1/2,
  // D = exp(-cot^2 h) / (pi sin^4 h) = exp(-1/3) / (pi 9/16); f = D G / (4 cos_o cos_i).
  const Vec3 wo = dir(b, 60.0f);
  const double d = std::exp(-1.0 / 3.0) / (kChi2Pi * 0.5625);
  EXPECT_NEAR(b.eval(wo, wo).x, 0.25 * d * 0.5 / 0.25, 1e-5);
  // Reciprocal, nothing below the surface, and brighter towards grazing (fibres seen side on).
  const Vec3 wi = dir(b, 40.0f, 2.0f);
  EXPECT_NEAR(b.eval(wo, wi).x, b.eval(wi, wo).x, 1e-6f * b.eval(wo, wi).x);
  EXPECT_EQ(b.eval(wo, -b.frame().n).x, 0.0f);
  EXPECT_GT(albedos(b, dir(b, 80.0f)).integrated, albedos(b, dir(b, 10.0f)).integrated);
  // Sigma is saturated and kept from 0 (Cycles: at least 0.01).
  const Bsdf tight = make({velvet(0.0f)}), at_min = make({velvet(0.01f)});
  EXPECT_EQ(tight.eval(wo, wi).x, at_min.eval(wo, wi).x);
}

TEST(PrincipledExtrasSheen, GrowsTowardsGrazingAsCyclesSheen) {
  const Bsdf b = make({sheen()});
  // f = (1 - wi.h)^5 without 1/pi: zero for retro-reflection, largest when wo and wi are far
  // apart (grazing), so the albedo grows steeply towards grazing.
  const Vec3 wo = dir(b, 60.0f);
  EXPECT_NEAR(b.eval(wo, wo).x, 0.0f, 1e-6f);
  const Vec3 wi = dir(b, 75.0f, 0.7f + 3.14159265f);
  const Vec3 h = normalize(wo + wi);
  EXPECT_NEAR(b.eval(wo, wi).x, std::pow(1.0f - dot(wi, h), 5.0f), 1e-5f);
  const double normal = albedos(b, b.frame().n).integrated;
  const double grazing = albedos(b, dir(b, 85.0f)).integrated;
  std::printf("  sheen albedo: normal %.4f, 85 deg %.4f\n", normal, grazing);
  EXPECT_GT(grazing, 100.0 * normal);
  EXPECT_GT(grazing, 0.05);
}

// f along a direction tilted 25 degrees from the normal towards azimuth `deg` (from kN's t),
// seen from the normal: the width of the highlight in that azimuth.
float highlight(const Bsdf& b, float deg) {
  const float a = deg * static_cast<float>(kChi2Pi / 180.0), t = 25.0f * 3.14159265f / 180.0f;
  const Frame f(kN);
  const Vec3 wi =
      f.to_world(Vec3(std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t)));
  return b.eval(kN, wi).x;
}

TEST(PrincipledExtrasAnisotropic, HighlightIsElongatedAlongTheTangent) {
  // alpha_x along the tangent: microfacet normals spread along it, so does the highlight.
  const Bsdf b = make({aniso_ggx(0.4f, 0.04f, tangent_at(35))});
  EXPECT_GT(highlight(b, 35), 20.0f * highlight(b, 125));
  EXPECT_NEAR(highlight(b, 35), highlight(b, 215), 1e-3f * highlight(b, 35));
  // Equal alphas: the isotropic lobe to float rounding.
  Lobe iso;
  iso.type = LobeType::kGgxReflection;
  iso.alpha = 0.2f;
  const Bsdf a = make({aniso_ggx(0.2f, 0.2f, tangent_at(10))});
  const Bsdf i = make({iso});
  for (float deg : {0.0f, 50.0f, 100.0f})
    EXPECT_NEAR(highlight(a, deg), highlight(i, deg), 1e-4f * highlight(i, deg));
}

// ---- material_eval: the inputs become these lobes ----

struct QuadFixture {
  explicit QuadFixture(Material m) {
    scene.materials.push_back(std::move(m));
    add_mesh_instance(&scene, make_textured_quad(), 0);
    accel = std::make_unique<Accel>(scene, nullptr);
    Ray ray;
    ray.origin = Vec3(0.1f, 0.2f, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    Hit hit;
    EXPECT_TRUE(accel->intersect(ray, kVisibleAll, &hit));
    si = accel->interaction(hit);
  }
  ShadingPoint shade(const Vec3& wo = Vec3(0, 0, 1)) const {
    return shade_surface(si, wo, *accel, nullptr);
  }
  Scene scene;
  std::unique_ptr<Accel> accel;
  SurfaceInteraction si;
};

Closure principled() {
  Closure c;
  c.type = ClosureType::kPrincipled;
  return c;
}

TEST(PrincipledExtrasMaterial, AnisotropicHighlightFollowsTheRotatedUvTangent) {
  for (float rotation : {0.125f, 0.375f}) {
    Closure c = principled();
    c[Param::kAnisotropic] = Input::constant(0.9f);
    c[Param::kAnisotropicRotation] = Input::constant(rotation);
    c[Param::kRoughness] = Input::constant(0.4f);
    c[Param::kMetallic] = Input::constant(1.0f);  // the specular lobe alone
    c[Param::kColor] = Input::constant(Vec3(1.0f));
    QuadFixture f(Material{"brushed", {c}});
    Vec3 dpdu, dpdv;
    ASSERT_TRUE(f.accel->uv_tangents(f.si.instance, f.si.primitive, &dpdu, &dpdv));
    const ShadingPoint sp = f.shade();
    ASSERT_EQ(sp.bsdf.lobe_count(), 1);
    const Lobe& s = sp.bsdf.lobe(0);
    ASSERT_TRUE(s.anisotropic());
    const float aspect = std::sqrt(1.0f - 0.9f * 0.9f);
    EXPECT_NEAR(s.alpha, std::min(0.16f / aspect, 1.0f), 1e-5f);
    EXPECT_NEAR(s.alpha_y, 0.16f * aspect, 1e-6f);
    // The highlight is long along dP/du turned by rotation x 360 degrees about the normal.
    const Vec3 n(0, 0, 1), t = normalize(dpdu), b = cross(n, t);
    const float a = rotation * 2.0f * 3.14159265f;
    const Vec3 along = t * std::cos(a) + b * std::sin(a), across = cross(n, along);
    const float tilt = 0.4f;
    const float f_along = sp.bsdf.eval(n, normalize(n + along * tilt)).x;
    const float f_across = sp.bsdf.eval(n, normalize(n + across * tilt)).x;
    EXPECT_GT(f_along, 3.0f * f_across) << rotation;
  }
}

TEST(PrincipledExtrasMaterial, SheenLobeIsWeightedAndTintedAsCycles) {
  Closure c = principled();
  c[Param::kColor] = Input::constant(Vec3(0.8f, 0.2f, 0.1f));
  c[Param::kSheen] = Input::constant(0.6f);
  c[Param::kSheenTint] = Input::constant(0.5f);
  c[Param::kMetallic] = Input::constant(0.25f);
  QuadFixture f(Material{"cloth", {c}});
  const ShadingPoint sp = f.shade();
  const Lobe* found = nullptr;
  for (int i = 0; i < sp.bsdf.lobe_count(); ++i)
    if (sp.bsdf.lobe(i).type == LobeType::kSheen) found = &sp.bsdf.lobe(i);
  ASSERT_NE(found, nullptr);
  const Vec3 base(0.8f, 0.2f, 0.1f);
  const Vec3 tint = lerp(Vec3(1.0f), base / luminance(base), 0.5f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(found->weight[k], tint[k] * 0.6f * 0.75f, 1e-5f);
}

TEST(PrincipledExtrasMaterial, TransmissionRoughnessSplitsTheGlass) {
  Closure c = principled();
  c[Param::kTransmission] = Input::constant(1.0f);
  c[Param::kRoughness] = Input::constant(0.2f);
  c[Param::kTransmissionRoughness] = Input::constant(0.5f);
  c[Param::kColor] = Input::constant(Vec3(1.0f));
  QuadFixture f(Material{"frosted", {c}});
  const Vec3 wo = normalize(Vec3(0.3f, 0.0f, 1.0f));
  const ShadingPoint sp = f.shade(wo);
  const Lobe* refl = nullptr;
  const Lobe* refr = nullptr;
  for (int i = 0; i < sp.bsdf.lobe_count(); ++i) {
    const Lobe& l = sp.bsdf.lobe(i);
    if (l.type == LobeType::kGgxRefraction) refr = &l;
    if (l.type == LobeType::kGgxReflection && l.fresnel == FresnelMode::kInterpolated) refl = &l;
  }
  ASSERT_NE(refl, nullptr);
  ASSERT_NE(refr, nullptr);
  const float fr = fresnel_dielectric(wo.z, 1.45f);
  EXPECT_NEAR(refl->alpha, 0.04f, 1e-6f);
  const float rt = 1.0f - 0.8f * 0.5f;
  EXPECT_NEAR(refr->alpha, rt * rt, 1e-6f);
  EXPECT_NEAR(refl->weight.x, fr, 1e-5f);
  EXPECT_NEAR(refr->weight.x, 1.0f - fr, 1e-5f);
}

TEST(PrincipledExtrasMaterial, SubsurfaceMixesTheDiffuseColour) {
  Closure c = principled();
  c[Param::kColor] = Input::constant(Vec3(0.2f, 0.4f, 0.6f));
  c[Param::kSubsurface] = Input::constant(0.25f);
  c[Param::kSubsurfaceColor] = Input::constant(Vec3(1.0f, 0.0f, 0.0f));
  QuadFixture f(Material{"skin", {c}});
  const ShadingPoint sp = f.shade();
  ASSERT_GE(sp.bsdf.lobe_count(), 1);
  const Lobe& d = sp.bsdf.lobe(0);
  ASSERT_EQ(d.type, LobeType::kBurleyDiffuse);
  EXPECT_NEAR(d.weight.x, 0.75f * 0.2f + 0.25f, 1e-6f);
  EXPECT_NEAR(d.weight.y, 0.75f * 0.4f, 1e-6f);
  EXPECT_NEAR(d.weight.z, 0.75f * 0.6f, 1e-6f);
}

TEST(PrincipledExtrasMaterial, DiffuseRoughnessIsOrenNayarAndZeroIsLambert) {
  for (float r : {0.0f, 0.7f}) {
    Closure c;
    c.type = ClosureType::kDiffuse;
    c[Param::kRoughness] = Input::constant(r);
    QuadFixture f(Material{"matte", {c}});
    const ShadingPoint sp = f.shade();
    ASSERT_EQ(sp.bsdf.lobe_count(), 1);
    EXPECT_EQ(sp.bsdf.lobe(0).type, r > 0.0f ? LobeType::kOrenNayar : LobeType::kLambert);
    EXPECT_NEAR(sp.bsdf.lobe(0).roughness, r, 1e-7f);
    EXPECT_FALSE(sp.bsdf.lobe(0).oren_nayar_multiscatter);
  }
  // Blender 4.3+: the multiple scattering term, of the node's colour (not its mix weight).
  Closure c;
  c.type = ClosureType::kDiffuse;
  c.diffuse_multiscatter = true;
  c[Param::kRoughness] = Input::constant(0.7f);
  c[Param::kColor] = Input::constant(Vec3(0.9f, 0.5f, 0.2f));
  c.weight = {{Input::constant(0.5f), false}};
  QuadFixture f(Material{"matte", {c}});
  const ShadingPoint sp = f.shade();
  const Lobe& l = sp.bsdf.lobe(0);
  EXPECT_TRUE(l.oren_nayar_multiscatter);
  EXPECT_NEAR(l.tint.x, 0.9f, 1e-6f);
  EXPECT_NEAR(l.tint.z, 0.2f, 1e-6f);
  EXPECT_NEAR(l.weight.x, 0.45f, 1e-6f);
}

TEST(PrincipledExtrasMaterial, AnisotropicBsdfNodeUsesCyclesAlphas) {
  for (float a : {0.6f, -0.6f}) {
    Closure c;
    c.type = ClosureType::kAnisotropic;
    c[Param::kRoughness] = Input::constant(0.5f);
    c[Param::kAnisotropic] = Input::constant(a);
    c[Param::kAnisotropicRotation] = Input::constant(0.0f);
    QuadFixture f(Material{"aniso", {c}});
    const ShadingPoint sp = f.shade();
    ASSERT_EQ(sp.bsdf.lobe_count(), 1);
    const Lobe& l = sp.bsdf.lobe(0);
    ASSERT_TRUE(l.anisotropic());
    const float r2 = 0.25f;
    EXPECT_NEAR(l.alpha, a > 0 ? r2 * (1 - a) : r2 / (1 + a), 1e-6f);
    EXPECT_NEAR(l.alpha_y, a > 0 ? r2 / (1 - a) : r2 * (1 + a), 1e-6f);
  }
}

TEST(PrincipledExtrasClearcoat, OwnNormalMovesTheHighlight) {
  // A sharp-ish coat on a normal tilted 20 degrees reflects about that normal, not kN.
  Lobe coat;
  coat.type = LobeType::kGgxReflection;
  coat.alpha = 0.01f;
  const Frame f(kN);
  const Vec3 n2 = f.to_world(Vec3(std::sin(0.35f), 0.0f, std::cos(0.35f)));
  coat.normal = n2;
  const Bsdf b = make({coat});
  const Vec3 wo = kN;
  const Vec3 mirror_n2 = normalize(n2 * (2.0f * dot(wo, n2)) - wo);
  EXPECT_GT(b.eval(wo, mirror_n2).x, 100.0f * b.eval(wo, wo).x);
}

// Cycles 4.3's Oren-Nayar: single scattering's directional albedo is Fujii's closed form
// pi A + B G(cos_o); with the multiple scattering term a white surface reflects all the light
// (up to the fitted E_avg), and a coloured one more than single scattering alone, by the
// series rho^2 E_avg (1 - E(cos_o)) / (1 - rho (1 - E_avg)).
TEST(PrincipledExtrasFurnace, EnergyPreservingOrenNayarPutsTheLostLightBack) {
  for (float sigma : {0.5f, 1.0f}) {
    const double a = 1.0 / (kChi2Pi + (kChi2Pi / 2.0 - 2.0 / 3.0) * sigma), b = sigma * a;
    const double e_avg = kChi2Pi * a + (2.0 * kChi2Pi - 5.6) / 3.0 * b;
    for (float theta : {0.0f, 45.0f, 80.0f}) {
      const Bsdf single = make({oren_nayar(sigma)});
      const Vec3 wo = dir(single, theta);
      const double e_o =
          kChi2Pi * a + b * bsdf_lobes::oren_nayar_g(std::cos(theta * kChi2Pi / 180));
      const double single_albedo = albedos(single, wo).integrated;
      EXPECT_NEAR(single_albedo, e_o, 2e-3) << sigma << " " << theta;

      const Bsdf white = make({oren_nayar_ms(sigma, Vec3(1.0f))});
      const Albedos w = albedos(white, wo);
      std::printf(
          "  sigma %.1f theta %4.1f single %.4f with multiple scattering %.4f (sampled "
          "%.4f +- %.4f)\n",
          sigma, theta, single_albedo, w.integrated, w.sampled, w.sampled_error);
      EXPECT_NEAR(w.integrated, 1.0, 3e-3) << sigma << " " << theta;
      EXPECT_NEAR(w.sampled, w.integrated, 4.0 * w.sampled_error + 2e-3);

      const double rho = 0.6;
      const Bsdf grey = make({oren_nayar_ms(sigma, Vec3(static_cast<float>(rho)))});
      const double expected =
          single_albedo + rho * rho * e_avg * (1.0 - e_o) / (1.0 - rho * (1.0 - e_avg));
      EXPECT_NEAR(albedos(grey, wo).integrated, expected, 3e-3) << sigma << " " << theta;
    }
  }
  // At sigma 0 it is Lambert, with or without the term.
  const Bsdf smooth = make({oren_nayar_ms(0.0f, Vec3(0.5f))});
  EXPECT_NEAR(albedos(smooth, dir(smooth, 30)).integrated, 1.0, 2e-3);
}

}  // namespace
}  // namespace principled_extras_test
}  // namespace photon

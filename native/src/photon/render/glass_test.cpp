// Glass as Cycles 3.4 builds it (svm/closure.h): the Glass BSDF and the Principled glass (with
// the default GGX distribution, whatever the Transmission Roughness) are a GGX reflection
// weighted by the dielectric Fresnel of the shading normal, F(wo.z), with F = 1 on the
// microfacets, and a GGX refraction weighted by 1 - F(wo.z) that returns nothing where the
// sampled microfacet reflects totally. The Principled reflection is tinted only by Specular
// Tint, its refraction by the base colour.

#include <gtest/gtest.h>

#include <memory>

#include "photon/base/microfacet.h"
#include "photon/base/optics.h"
#include "photon/render/bsdf.h"
#include "photon/render/bsdf_chi2_util.h"
#include "photon/render/material_eval.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace glass_test {
namespace {

using bsdf_chi2::Uniform;

// ---- The glass lobe (Glass BSDF) ----

Lobe lobe(LobeType type, float alpha, const Vec3& weight = Vec3(1.0f)) {
  Lobe l;
  l.type = type;
  l.weight = weight;
  l.alpha = alpha;
  l.ior = 1.5f;
  return l;
}

Bsdf single(const Lobe& l, bool front) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  Bsdf b(n, n, front);
  b.add(l);
  return b;
}

Vec3 direction(float theta_deg, float phi) {
  const float t = theta_deg * 3.14159265f / 180.0f;
  return Vec3(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t));
}

// Its reflection is F(wo.z) times GGX reflection with F = 1, and its transmission 1 - F(wo.z)
// times the Refraction lobe, outside and inside, at every pair of directions (a microfacet
// Fresnel F(wo.h) differs away from the mirror direction).
TEST(GlassLobe, IsTheMacroFresnelSplitOfReflectionAndRefraction) {
  Uniform rng(5);
  for (bool front : {true, false}) {
    const float eta = front ? 1.5f : 1.0f / 1.5f;
    for (float alpha : {0.09f, 0.36f}) {
      const Bsdf glass = single(lobe(LobeType::kGgxGlass, alpha), front);
      const Bsdf mirror = single(lobe(LobeType::kGgxReflection, alpha), front);
      const Bsdf refraction = single(lobe(LobeType::kGgxRefraction, alpha), front);
      int checked = 0;
      for (int i = 0; i < 400; ++i) {
        const Vec3 wo = direction(85.0f * rng.next(), 6.28f * rng.next());
        Vec3 wi = direction(89.0f * rng.next(), 6.28f * rng.next());
        if (i % 2) wi = -wi;
        const float f = fresnel_dielectric(wo.z, eta);
        const Vec3 expected =
            wi.z > 0.0f ? mirror.eval(wo, wi) * f : refraction.eval(wo, wi) * (1.0f - f);
        const Vec3 got = glass.eval(wo, wi);
        ASSERT_NEAR(got.x, expected.x, 1e-4f * std::max(1.0f, expected.x))
            << front << " " << alpha << " " << i;
        // The pdf follows: reflection chosen with probability F(wo.z).
        const float pdf_expected =
            wi.z > 0.0f ? mirror.pdf(wo, wi) * f : refraction.pdf(wo, wi) * (1.0f - f);
        ASSERT_NEAR(glass.pdf(wo, wi), pdf_expected, 1e-4f * std::max(1.0f, pdf_expected));
        if (expected.x > 1e-3f) ++checked;
      }
      EXPECT_GT(checked, 100);
    }
  }
}

// Sampled from inside near the critical angle, the refraction of a rough interface loses what
// its microfacets reflect totally: the lobe's albedo is below the Walter glass's (which would
// reflect it), as Cycles 3.4's split closures lose it.
TEST(GlassLobe, RefractionIntoTotallyReflectingMicrofacetsIsLost) {
  const Bsdf glass = single(lobe(LobeType::kGgxGlass, 0.25f), false);
  const Vec3 wo = direction(40.0f, 0.0f);  // critical angle of 1.5 is 41.8 degrees
  const float f = fresnel_dielectric(wo.z, 1.0f / 1.5f);
  Uniform rng(3);
  double reflected = 0.0, transmitted = 0.0, lost = 0.0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float u_lobe = rng.next();
    const Vec2 u = rng.next_2d();
    if (!glass.sample(wo, u_lobe, u, kLobeAll, &s)) {
      if (u_lobe >= f) lost += 1.0 / n;
      continue;
    }
    (s.wi.z > 0.0f ? reflected : transmitted) += s.weight.x / n;
  }
  EXPECT_GT(lost, 0.1);  // a good share of the refraction samples meet total reflection
  EXPECT_LT(reflected, f + 0.01);
  EXPECT_LT(reflected + transmitted, 0.9);
}

// ---- The Principled glass ----
// A Principled material on a quad in the z = 0 plane, shaded where a ray down -z hits it.
struct GlassQuad {
  explicit GlassQuad(const Closure& c) {
    scene.materials.push_back(Material{"glass", {c}});
    add_mesh_instance(&scene, make_textured_quad(), 0);
    accel = std::make_unique<Accel>(scene, nullptr);
    Ray ray;
    ray.origin = Vec3(0.1f, 0.2f, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    Hit hit;
    EXPECT_TRUE(accel->intersect(ray, kVisibleAll, &hit));
    si = accel->interaction(hit);
  }
  ShadingPoint shade(const Vec3& wo) const { return shade_surface(si, wo, *accel, nullptr); }
  Scene scene;
  std::unique_ptr<Accel> accel;
  SurfaceInteraction si;
};

Closure glass(float roughness, const Vec3& base, float specular_tint = 0.0f) {
  Closure c;
  c.type = ClosureType::kPrincipled;
  c[Param::kTransmission] = Input::constant(1.0f);
  c[Param::kRoughness] = Input::constant(roughness);
  c[Param::kTransmissionRoughness] = Input::constant(0.0f);
  c[Param::kSpecularTint] = Input::constant(specular_tint);
  c[Param::kColor] = Input::constant(base);
  return c;
}

struct Split {
  const Lobe* reflection = nullptr;
  const Lobe* refraction = nullptr;
  int glass_lobes = 0;
};

Split find_split(const Bsdf& b) {
  Split s;
  for (int i = 0; i < b.lobe_count(); ++i) {
    const Lobe& l = b.lobe(i);
    if (l.type == LobeType::kGgxReflection && l.fresnel == FresnelMode::kInterpolated)
      s.reflection = &l;
    if (l.type == LobeType::kGgxRefraction) s.refraction = &l;
    if (l.type == LobeType::kGgxGlass) ++s.glass_lobes;
  }
  return s;
}

// Transmission Roughness 0 is no special case: the refraction keeps Roughness, and the
// reflection is weighted by the macro-normal Fresnel, untinted by the base colour.
TEST(PrincipledGlass, TransmissionRoughnessZeroIsSplitLikeCycles) {
  const Vec3 base(0.9f, 0.5f, 0.2f);
  const GlassQuad quad(glass(0.3f, base));
  const Vec3 wo = normalize(Vec3(0.6f, 0.0f, 1.0f));
  const ShadingPoint sp = quad.shade(wo);
  const Split s = find_split(sp.bsdf);
  EXPECT_EQ(s.glass_lobes, 0);
  ASSERT_NE(s.reflection, nullptr);
  ASSERT_NE(s.refraction, nullptr);
  const float fr = fresnel_dielectric(wo.z, 1.45f);
  EXPECT_NEAR(s.reflection->alpha, 0.09f, 1e-6f);
  EXPECT_NEAR(s.refraction->alpha, 0.09f, 1e-6f);
  EXPECT_NEAR(s.refraction->ior, 1.45f, 1e-6f);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.reflection->weight[k], fr, 1e-5f) << k;
    EXPECT_NEAR(s.refraction->weight[k], base[k] * (1.0f - fr), 1e-5f) << k;
  }
}

// Specular Tint tints the reflection's microfacets towards the base colour (Cycles' cspec0).
TEST(PrincipledGlass, SpecularTintTintsTheReflection) {
  const Vec3 base(0.9f, 0.5f, 0.2f);
  const GlassQuad quad(glass(0.2f, base, 0.5f));
  const Vec3 wo(0.0f, 0.0f, 1.0f);
  const ShadingPoint sp = quad.shade(wo);  // the Split points into its lobes
  const Split s = find_split(sp.bsdf);
  ASSERT_NE(s.reflection, nullptr);
  const float fr = fresnel_dielectric(1.0f, 1.45f);
  EXPECT_NEAR(s.reflection->ior, 1.45f, 1e-6f);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.reflection->weight[k], fr, 1e-5f) << k;
    EXPECT_NEAR(s.reflection->f0[k], 0.5f + 0.5f * base[k], 1e-5f) << k;
  }
}

// Cycles' interpolate_fresnel_color: the tint at normal incidence, blended to white by the
// normalised dielectric Fresnel of the microfacet, white where it reflects totally (inside).
TEST(GlassLobe, InterpolatedFresnelGoesFromTheTintToWhite) {
  const Vec3 tint(0.95f, 0.75f, 0.6f);
  Lobe l = lobe(LobeType::kGgxReflection, 0.0f);  // a mirror: the sample weight is F(wo.z)
  l.fresnel = FresnelMode::kInterpolated;
  l.f0 = tint;
  const float f0 = fresnel_dielectric(1.0f, 1.5f);
  struct Case {
    bool front;
    float theta;
  };
  for (const Case c :
       {Case{true, 0.0f}, Case{true, 80.0f}, Case{false, 30.0f}, Case{false, 60.0f}}) {
    const Bsdf b = single(l, c.front);
    const Vec3 wo = direction(c.theta, 0.0f);
    BsdfSample s;
    ASSERT_TRUE(b.sample(wo, 0.5f, Vec2(0.5f, 0.5f), kLobeAll, &s));
    const float fh = (fresnel_dielectric(wo.z, c.front ? 1.5f : 1.0f / 1.5f) - f0) / (1.0f - f0);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(s.weight[k], tint[k] + (1.0f - tint[k]) * fh, 1e-5f) << c.theta << " " << k;
    if (c.theta == 0.0f) EXPECT_NEAR(s.weight.y, tint.y, 1e-5f);
    if (!c.front && c.theta == 60.0f) EXPECT_NEAR(s.weight.z, 1.0f, 1e-5f);  // total reflection
  }
}

// Smooth coloured glass: the mirror reflection carries F of white light (the single glass lobe
// tinted it by the base colour), the refraction (1 - F) of the base colour. Stratified over the
// lobe choice, the mean sample weight of each event is its throughput.
TEST(PrincipledGlass, SmoothGlassReflectsWhiteAndRefractsTheBaseColour) {
  const Vec3 base(0.9f, 0.5f, 0.2f);
  const GlassQuad quad(glass(0.0f, base));
  const Vec3 wo = normalize(Vec3(0.8f, 0.0f, 1.0f));
  const ShadingPoint sp = quad.shade(wo);
  const float fr = fresnel_dielectric(wo.z, 1.45f);
  Vec3 reflected(0.0f), refracted(0.0f);
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    ASSERT_TRUE(sp.bsdf.sample(wo, (i + 0.5f) / n, Vec2(0.5f, 0.5f), kLobeAll, &s));
    ASSERT_TRUE(s.is_delta());
    (s.wi.z > 0.0f ? reflected : refracted) += s.weight / float(n);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(reflected[k], fr, 2e-3f) << k;
    EXPECT_NEAR(refracted[k], (1.0f - fr) * base[k], 2e-3f) << k;
  }
}

}  // namespace
}  // namespace glass_test
}  // namespace photon

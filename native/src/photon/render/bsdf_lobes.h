// The lobes of a BSDF one by one: their f, pdf and sampling, shared by Bsdf (RGB) and
// SpectralBsdf (sampled wavelengths). Colours are a template parameter C: Vec3 for RGB, a
// SampledSpectrum for all wavelengths of a path at once, or a float for one wavelength (a
// dispersive lobe, whose index of refraction differs per wavelength). The Vec3 instantiation
// computes exactly what the RGB renderer always did. Internal to render/: include it only from
// the BSDF's own sources.
#pragma once

#include <algorithm>
#include <cmath>

#include "photon/base/microfacet.h"
#include "photon/base/microfacet_beckmann.h"
#include "photon/base/optics.h"
#include "photon/base/sampling.h"
#include "photon/render/bsdf.h"

namespace photon::bsdf_lobes {

// Below this distance from 1 a relative index of refraction leaves directions unchanged: the
// glass and refraction lobes are then delta lobes whatever their roughness (a rough interface
// with equal indices refracts every microfacet straight through).
constexpr float kUnitEtaEpsilon = 1e-4f;

inline bool is_unit_direction(const Vec3& w) {
  const float l2 = length_squared(w);
  return std::isfinite(l2) && l2 > 1e-12f;
}

// Normalises only when needed, so a direction that sample() returned maps to bit-identical
// local coordinates in pdf() and eval() (near total internal reflection 1 - F is steep enough
// for an ulp to show).
inline Vec3 unit(const Vec3& w) {
  const float l2 = length_squared(w);
  return std::fabs(l2 - 1.0f) < 4e-7f ? w : w / std::sqrt(l2);
}

// The largest GGX alpha of a lobe (both axes of an anisotropic one).
inline float max_alpha(const Lobe& l) {
  return l.anisotropic() ? std::max(l.alpha, l.alpha_y) : l.alpha;
}

inline bool is_delta(const Lobe& l) {
  switch (l.type) {
    case LobeType::kGgxReflection:
      return max_alpha(l) < kDeltaAlpha;
    case LobeType::kGgxGlass:
    case LobeType::kGgxRefraction:
    case LobeType::kGgxDielectric:
      return l.alpha < kDeltaAlpha || std::fabs(l.ior - 1.0f) < kUnitEtaEpsilon;
    case LobeType::kTransparent:
      return true;
    default:
      return false;
  }
}

// The microfacet functions of a lobe: Beckmann's for a Beckmann lobe (isotropic as ax == ay),
// else GGX's, anisotropic ones with both alphas (the isotropic path keeps the isotropic
// functions, so isotropic lobes are unchanged to the bit).
inline float lobe_alpha_y(const Lobe& l) {
  return l.anisotropic() ? l.alpha_y : l.alpha;
}
inline float lobe_d(const Lobe& l, const Vec3& h) {
  if (l.beckmann) return beckmann_d(h, l.alpha, lobe_alpha_y(l));
  return l.anisotropic() ? ggx_d(h, l.alpha, l.alpha_y) : ggx_d(h, l.alpha);
}
inline float lobe_lambda(const Lobe& l, const Vec3& w) {
  if (l.beckmann) return beckmann_lambda_approx(w, l.alpha, lobe_alpha_y(l));
  return l.anisotropic() ? ggx_lambda(w, l.alpha, l.alpha_y) : ggx_lambda(w, l.alpha);
}
inline float lobe_g2(const Lobe& l, const Vec3& wo, const Vec3& wi, const Vec3& h) {
  if (l.correlated) {
    // Both directions on the front of their microfacet side (as G1's test), then
    // 1 / (1 + L(wo) + L(wi)); L is even in w.z, so refracted directions read alike.
    if (dot(wo, h) * wo.z <= 0.0f || dot(wi, h) * wi.z <= 0.0f) return 0.0f;
    return 1.0f / (1.0f + lobe_lambda(l, wo) + lobe_lambda(l, wi));
  }
  if (l.beckmann) {
    const float ay = lobe_alpha_y(l);
    return beckmann_g1(wo, h, l.alpha, ay) * beckmann_g1(wi, h, l.alpha, ay);
  }
  if (!l.anisotropic()) return ggx_g2(wo, wi, h, l.alpha);
  return ggx_g1(wo, h, l.alpha, l.alpha_y) * ggx_g1(wi, h, l.alpha, l.alpha_y);
}
inline float lobe_visible_normal_pdf(const Lobe& l, const Vec3& wo, const Vec3& h) {
  if (l.beckmann) return beckmann_visible_normal_pdf(wo, h, l.alpha, lobe_alpha_y(l));
  return l.anisotropic() ? ggx_visible_normal_pdf(wo, h, l.alpha, l.alpha_y)
                         : ggx_visible_normal_pdf(wo, h, l.alpha);
}
inline Vec3 lobe_sample_visible_normal(const Lobe& l, const Vec3& wo, Vec2 u) {
  if (l.beckmann) return beckmann_sample_visible_normal(wo, l.alpha, lobe_alpha_y(l), u);
  return l.anisotropic() ? ggx_sample_visible_normal(wo, l.alpha, l.alpha_y, u)
                         : ggx_sample_visible_normal(wo, l.alpha, u);
}

// Per-channel clamp to [0, 1] (SampledSpectrum's overload lives beside it, found by ADL).
inline float saturate_channels(float v) {
  return std::clamp(v, 0.0f, 1.0f);
}
inline Vec3 saturate_channels(const Vec3& v) {
  return {std::clamp(v.x, 0.0f, 1.0f), std::clamp(v.y, 0.0f, 1.0f), std::clamp(v.z, 0.0f, 1.0f)};
}

// kSchlickIor's interpolation factor s at cosine `c` for relative IOR `eta`.
inline float schlick_ior_s(float c, float eta) {
  const float r = (eta - 1.0f) / (eta + 1.0f);
  const float r0 = r * r;
  if (!(1.0f - r0 > 0.0f)) return 1.0f;
  return std::clamp((fresnel_dielectric(c, eta) - r0) / (1.0f - r0), 0.0f, 1.0f);
}

// kF82Tint at cosine `c`: Schlick's F0 .. 1 blend less b c (1 - c)^6, where b makes the value at
// c = 1/7 Schlick's times `tint`: b = F_schlick(1/7) (1 - tint) / ((1/7) (6/7)^6).
template <class C>
C f82_tint_fresnel(const C& f0, const C& tint, float c) {
  const float mu = std::clamp(1.0f - c, 0.0f, 1.0f);
  const float mu5 = (mu * mu) * (mu * mu) * mu;
  constexpr float f = 6.0f / 7.0f;
  constexpr float f5 = (f * f) * (f * f) * f;
  const C b = (f0 + (C(1.0f) - f0) * f5) * (7.0f / (f5 * f)) * (C(1.0f) - tint);
  return saturate_channels(f0 + (C(1.0f) - f0) * mu5 - b * (c * mu5 * mu));
}

// Fresnel of a kGgxReflection lobe at the microfacet cosine `cos_oh`.
// `f0` is the lobe's f0 in the colour type C (Vec3, a SampledSpectrum or one wavelength's float).
template <class C>
C reflection_fresnel(const Lobe& l, const C& f0, float cos_oh, float eta, const C& tint) {
  switch (l.fresnel) {
    case FresnelMode::kSchlickIor:
      return f0 + (C(1.0f) - f0) * schlick_ior_s(cos_oh, eta);
    case FresnelMode::kF82Tint:
      return f82_tint_fresnel(f0, tint, cos_oh);
    case FresnelMode::kDielectric:
      return C(fresnel_dielectric(cos_oh, eta));
    case FresnelMode::kSchlick:
      return f0 + (C(1.0f) - f0) * schlick_weight(cos_oh);  // fresnel_schlick
    case FresnelMode::kInterpolated: {
      const float f_normal = fresnel_dielectric(1.0f, eta);
      const float fh =
          f_normal < 1.0f ? (fresnel_dielectric(cos_oh, eta) - f_normal) / (1.0f - f_normal) : 1.0f;
      return f0 + (C(1.0f) - f0) * fh;
    }
    default:
      return C(1.0f);
  }
}

// Where the generalized half vector of a refraction (Walter 2007, eq. 16) is valid: wo above,
// wi below, both on the front of the microfacet h (oriented to +z). `eta` = n_wi / n_wo.
struct RefractionGeometry {
  Vec3 h;
  float cos_oh = 0.0f, cos_ih = 0.0f;
  float denom2 = 0.0f;  // (wo.h + eta wi.h)^2
  bool valid = false;
};

inline RefractionGeometry refraction_geometry(const Vec3& wo, const Vec3& wi, float eta) {
  RefractionGeometry g;
  Vec3 h = wo + wi * eta;
  const float l2 = length_squared(h);
  if (!(l2 > 1e-12f)) return g;
  h = h / std::sqrt(l2);
  if (h.z < 0.0f) h = -h;
  g.h = h;
  g.cos_oh = dot(wo, h);
  g.cos_ih = dot(wi, h);
  if (g.cos_oh <= 0.0f || g.cos_ih >= 0.0f) return g;
  const float d = g.cos_oh + eta * g.cos_ih;
  g.denom2 = d * d;
  g.valid = g.denom2 > 1e-20f;
  return g;
}

template <class C>
struct LobeEval {
  C f{0.0f};         // f(wo, wi) without the cosine
  float pdf = 0.0f;  // solid-angle density of this lobe's sampling routine
};

// The share of a glass lobe that reflects: Cycles 3.4's Glass BSDF (svm/closure.h) weights
// its GGX reflection closure by the dielectric Fresnel of the shading normal, F(wo.z), and its
// GGX refraction closure by 1 - F(wo.z); neither applies a Fresnel term per microfacet.
inline float glass_fresnel(const Vec3& wo, float eta) {
  return fresnel_dielectric(wo.z, eta);
}

// Microfacet reflection (Walter 2007, eq. 20) of a GGX reflection or glass lobe, wo.z and wi.z
// > 0, with the pdf of visible-normal sampling (Heitz 2018, eq. 17 and the reflection
// Jacobian 1 / (4 wo.h)). Glass picks reflection with probability F(wo.z).
template <class C>
LobeEval<C> ggx_reflection(const Lobe& l, const C& weight, const C& f0, const C& tint,
                           const Vec3& wo, const Vec3& wi, float eta) {
  LobeEval<C> r;
  const Vec3 h = normalize(wo + wi);
  const float cos_oh = dot(wo, h);
  if (cos_oh <= 0.0f) return r;
  const float d = lobe_d(l, h);
  const float g = lobe_g2(l, wo, wi, h);
  const bool glass = l.type == LobeType::kGgxGlass;
  const float fg = glass ? glass_fresnel(wo, eta) : 1.0f;
  const C fr = glass ? C(fg) : reflection_fresnel(l, f0, cos_oh, eta, tint);
  r.f = weight * fr * (d * g / (4.0f * wo.z * wi.z));
  r.pdf = lobe_visible_normal_pdf(l, wo, h) / (4.0f * cos_oh) * fg;
  return r;
}

// Microfacet refraction (Walter 2007, eq. 21) without the radiance scaling 1/eta^2 (see
// bsdf.h), wo.z > 0 > wi.z; the pdf uses the refraction Jacobian (eq. 17). Glass weights it by
// 1 - F(wo.z) (and picks it with that probability); the Refraction lobe refracts everything.
// Where the sampled microfacet reflects totally, neither returns light (as in Cycles 3.4).
template <class C>
LobeEval<C> ggx_transmission(const Lobe& l, const C& weight, const Vec3& wo, const Vec3& wi,
                             float eta) {
  LobeEval<C> r;
  const RefractionGeometry geo = refraction_geometry(wo, wi, eta);
  if (!geo.valid) return r;
  const float d = lobe_d(l, geo.h);
  const float g = lobe_g2(l, wo, wi, geo.h);
  const float t = l.type == LobeType::kGgxGlass ? 1.0f - glass_fresnel(wo, eta) : 1.0f;
  const float jacobian = eta * eta * std::fabs(geo.cos_ih) / geo.denom2;  // d(h) / d(wi)
  r.f = weight * (t * d * g * jacobian * geo.cos_oh / (wo.z * std::fabs(wi.z)));
  r.pdf = t * lobe_visible_normal_pdf(l, wo, geo.h) * jacobian;
  return r;
}

// kGgxDielectric's reflectance R and transmittance T at microfacet cosine `c` in the colour
// type C, and its probability of reflecting, from the lobe's RGB colours (so every colour model
// samples the same events).
template <class C>
void dielectric_split(const Lobe& /*l*/, const C& f0, const C& tint, float c, float eta, C* r,
                      C* t) {
  const float s = schlick_ior_s(c, eta);
  *r = f0 + (C(1.0f) - f0) * s;
  *t = (C(1.0f) - *r) * tint;
}
inline float dielectric_reflect_probability(const Lobe& l, float c, float eta) {
  Vec3 r, t;
  dielectric_split(l, l.f0, l.tint, c, eta, &r, &t);
  const float total = (r.x + r.y + r.z) + (t.x + t.y + t.z);
  return total > 0.0f ? (r.x + r.y + r.z) / total : 1.0f;
}

// kGgxDielectric at wo.z > 0 (Walter et al. 2007, eqs. 20 and 21 with the Fresnel of the
// microfacet), height-correlated or separable G as the lobe says.
template <class C>
LobeEval<C> ggx_dielectric(const Lobe& l, const C& weight, const C& f0, const C& tint,
                           const Vec3& wo, const Vec3& wi, float eta) {
  LobeEval<C> e;
  C r, t;
  if (wi.z > 0.0f) {
    const Vec3 h = normalize(wo + wi);
    const float cos_oh = dot(wo, h);
    if (cos_oh <= 0.0f) return e;
    dielectric_split(l, f0, tint, cos_oh, eta, &r, &t);
    const float pr = dielectric_reflect_probability(l, cos_oh, eta);
    const float d = lobe_d(l, h);
    e.f = weight * r * (d * lobe_g2(l, wo, wi, h) / (4.0f * wo.z * wi.z));
    e.pdf = pr * lobe_visible_normal_pdf(l, wo, h) / (4.0f * cos_oh);
    return e;
  }
  const RefractionGeometry geo = refraction_geometry(wo, wi, eta);
  if (!geo.valid) return e;
  dielectric_split(l, f0, tint, geo.cos_oh, eta, &r, &t);
  const float pt = 1.0f - dielectric_reflect_probability(l, geo.cos_oh, eta);
  const float d = lobe_d(l, geo.h);
  const float g = lobe_g2(l, wo, wi, geo.h);
  const float jacobian = eta * eta * std::fabs(geo.cos_ih) / geo.denom2;
  e.f = weight * t * (d * g * jacobian * geo.cos_oh / (wo.z * std::fabs(wi.z)));
  e.pdf = pt * lobe_visible_normal_pdf(l, wo, geo.h) * jacobian;
  return e;
}

// Chiang, Li & Burley 2019, "Taming the Shadow Terminator", eq. 4 with its smooth cubic
// (eq. 5): G = min(1, (Ns.wi) / ((Nb.wi)(Ns.Nb))) for the smooth normal Ns and the bumped
// normal Nb, smoothed as -G^3 + G^2 + G; 0 when wi is below the smooth surface.
inline float bump_shadowing(const Vec3& smooth_n, const Vec3& bumped_n, const Vec3& wi) {
  const float denominator = dot(bumped_n, wi) * dot(smooth_n, bumped_n);
  const float g = denominator != 0.0f ? dot(smooth_n, wi) / denominator : 0.0f;
  if (!(g < 1.0f)) return g >= 1.0f ? 1.0f : 0.0f;  // NaN: black
  if (g < 0.0f) return 0.0f;
  return g * (1.0f + g - g * g);
}

// `f` applied to each channel (SampledSpectrum's overload lives beside it, found by ADL).
template <class F>
float map_channels(float v, F f) {
  return f(v);
}
template <class F>
Vec3 map_channels(const Vec3& v, F f) {
  return {f(v.x), f(v.y), f(v.z)};
}

// Fujii's G(theta) = sin(theta) (theta - 2/3 - sin(theta) cos(theta)) + 2/3 tan(theta) (1 -
// sin^3(theta)): the improved Oren-Nayar's directional albedo is pi A + B G(cos theta). Near
// grazing tan() blows up, where the first terms of its expansion pi/2 - 2/3 - cos(theta) serve.
inline float oren_nayar_g(float cos_theta) {
  if (cos_theta < 1e-6f) return (0.5f * kPi - 2.0f / 3.0f) - cos_theta;
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float theta = std::acos(std::min(cos_theta, 1.0f));
  return sin_theta * (theta - 2.0f / 3.0f - sin_theta * cos_theta) +
         (2.0f / 3.0f) * (sin_theta / cos_theta) * (1.0f - sin_theta * sin_theta * sin_theta);
}

// The Oren-Nayar lobe's f / weight (local frame, both directions above). Single scattering is
// Fujii's improved Oren-Nayar (https://mimosa-pudica.net/improved-oren-nayar.html), as Cycles
// 3.4 evaluates it: A + B t with s = wi.wo - cos_i cos_o, t = s / max(cos_i, cos_o) where s > 0
// (else s), A = 1 / (pi + (pi/2 - 2/3) sigma), B = sigma A. With `oren_nayar_multiscatter`
// the energy it loses, 1 - E(cos), comes back as OpenPBR's multiple scattering lobe (as Cycles
// 4.3+): f_ms = E_ms (1 - E(cos_i)) (1 - E(cos_o)) with E_ms = rho^2 E_avg / (pi (1 - E_avg)
// (1 - rho (1 - E_avg))), E_avg = pi A + (2 pi - 5.6) / 3 B, rho = the albedo (`albedo`).
template <class C>
C oren_nayar(const Lobe& l, const C& albedo, const Vec3& wo, const Vec3& wi) {
  const float sigma = l.roughness;
  const float a = 1.0f / (kPi + ((3.0f * kPi - 4.0f) / 6.0f) * sigma);  // pi/2 - 2/3
  const float b = sigma * a;
  float t = dot(wi, wo) - wi.z * wo.z;
  if (t > 0.0f) t /= std::max(wi.z, wo.z);
  const float single = std::max(a + b * t, 0.0f);
  if (!l.oren_nayar_multiscatter || b <= 0.0f) return C(single);
  const float e_avg = kPi * a + ((2.0f * kPi - 5.6f) / 3.0f) * b;
  const float lost =
      (1.0f - (kPi * a + b * oren_nayar_g(wi.z))) * (1.0f - (kPi * a + b * oren_nayar_g(wo.z)));
  return map_channels(albedo, [&](float rho) {
    rho = std::clamp(rho, 0.0f, 1.0f);
    const float e_ms =
        kInvPi * rho * rho * (e_avg / (1.0f - e_avg)) / (1.0f - rho * (1.0f - e_avg));
    return single + e_ms * lost;
  });
}

// The cosine-weighted mean over the hemisphere above the bumped normal of bump_shadowing(), as
// a function of the cosine between the smooth and the bumped normal: the share of a bumped
// diffuse lobe's reflection the shadowing term leaves under even lighting (0.98 at 5 degrees of
// tilt, 0.82 at 31, 0.74 at 45). Tabulated once and interpolated (bsdf.cpp).
float bump_shadowing_mean(float cos_smooth_bumped);

// Directional albedo over the weight of the Burley diffuse lobe at cos_o, in closed form (the
// photon map multiplies its irradiance estimates by it; the colour alone is Lambert's answer).
// With F = (1 - cos)^5 and a = F_D90 - 1 = r (1 + wi.wo) - 1/2, f pi / weight = (1 + a F_i)
// (1 + a F_o). Averaged over wi's azimuth, E[wi.wo] = cos_i cos_o and E[(wi.wo)^2] =
// cos_i^2 cos_o^2 + sin_i^2 sin_o^2 / 2; the cosine moments of F_i are int_0^1 mu^k (1 - mu)^5
// dmu = k! 5! / (k + 6)! (1/42, 1/168, 1/504 for k = 1, 2, 3). For r = 1: 1.036 seen along the
// normal, 1.56 at grazing.
inline float burley_albedo(float roughness, float cos_o) {
  constexpr float m1 = 1.0f / 42.0f, m2 = 1.0f / 168.0f, m3 = 1.0f / 504.0f;
  const float v = std::clamp(cos_o, 0.0f, 1.0f), r = roughness, fo = schlick_weight(v);
  const float s2 = 1.0f - v * v;
  // int_0^1 mu E[a] F_i dmu, int_0^1 mu E[a] dmu and int_0^1 mu E[a^2] F_i dmu, where E[a^2] =
  // 1/4 - r E[1 + wi.wo] + r^2 E[(1 + wi.wo)^2].
  const float a_f = -0.5f * m1 + r * (m1 + v * m2);
  const float a_1 = -0.25f + r * (0.5f + v / 3.0f);
  const float sq = (1.0f + 0.5f * s2) * m1 + 2.0f * v * m2 + (v * v - 0.5f * s2) * m3;
  const float a2_f = 0.25f * m1 - r * (m1 + v * m2) + r * r * sq;
  return 1.0f + 2.0f * a_f + 2.0f * fo * (a_1 + a2_f);
}

// Directional albedo over the weight of the Oren-Nayar lobe at cos_o: pi A + B G(cos_o) for
// Fujii's single scattering, plus with `oren_nayar_multiscatter` the multiple scattering lobe's
// E_ms (1 - E(cos_o)) pi (1 - E_avg) (names as in oren_nayar()).
template <class C>
C oren_nayar_albedo(const Lobe& l, const C& albedo, float cos_o) {
  const float sigma = l.roughness;
  const float a = 1.0f / (kPi + ((3.0f * kPi - 4.0f) / 6.0f) * sigma);
  const float b = sigma * a;
  const float e = kPi * a + b * oren_nayar_g(std::clamp(cos_o, 0.0f, 1.0f));
  if (!l.oren_nayar_multiscatter || b <= 0.0f) return C(e);
  const float e_avg = kPi * a + ((2.0f * kPi - 5.6f) / 3.0f) * b;
  return map_channels(albedo, [&](float rho) {
    rho = std::clamp(rho, 0.0f, 1.0f);
    return e + (1.0f - e) * rho * rho * e_avg / (1.0f - rho * (1.0f - e_avg));
  });
}

// The directional albedo at cos_o of a lobe with kLobeDiffuse, in the colour type C.
template <class C>
C diffuse_lobe_albedo(const Lobe& l, const C& weight, const C& tint, float cos_o) {
  switch (l.type) {
    case LobeType::kBurleyDiffuse:
      return weight * burley_albedo(l.roughness, cos_o);
    case LobeType::kOrenNayar:
      return weight * oren_nayar_albedo(l, tint, cos_o);
    default:
      return weight;
  }
}

// The lobes Cycles counts as diffuse closures (CLOSURE_IS_BSDF_DIFFUSE).
// Cycles' Ashikhmin velvet f (kVelvet) with Sigma `sigma`, local frame, both directions above.
inline float velvet(float sigma, const Vec3& wo, const Vec3& wi) {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  const float s = std::max(std::min(sigma, 1.0f), 0.01f);
  const float inv_s2 = 1.0f / (s * s);
  const Vec3 h = normalize(wo + wi);
  const float cos_h = h.z, cos_oh = std::fabs(dot(wo, h));
  if (!(std::fabs(cos_h) < 1.0f - 1e-5f && cos_oh > 1e-5f)) return 0.0f;
  const float ratio = std::max(cos_h / cos_oh, 1e-5f);
  const float g = std::min(1.0f, std::min(2.0f * ratio * wo.z, 2.0f * ratio * wi.z));
  const float sin2 = 1.0f - cos_h * cos_h;
  const float d = std::exp(-(cos_h * cos_h / sin2) * inv_s2) * inv_s2 * kInvPi / (sin2 * sin2);
  return 0.25f * d * g / (wo.z * wi.z);
}

inline bool is_diffuse_type(const Lobe& l) {
  return l.type == LobeType::kLambert || l.type == LobeType::kBurleyDiffuse ||
         l.type == LobeType::kTranslucent;
}

// f and pdf of one non-delta lobe, in the local frame (wo.z > 0). `reflect` is the geometric
// classification of the pair; a lobe only contributes where the shading frame agrees with it.
// `weight` and `f0` are the lobe's colours in the colour type C.
template <class C>
LobeEval<C> eval_lobe(const Lobe& l, const C& weight, const C& f0, const C& tint, const Vec3& wo,
                      const Vec3& wi, bool reflect, float eta) {
  LobeEval<C> r;
  const bool shading_reflect = reflect && wi.z > 0.0f;
  const bool shading_transmit = !reflect && wi.z < 0.0f;
  switch (l.type) {
    case LobeType::kLambert:
      if (!shading_reflect) break;
      r.f = weight * kInvPi;
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    case LobeType::kBurleyDiffuse: {
      if (!shading_reflect) break;
      // Burley 2012, "Physically-Based Shading at Disney", sec. 5.3, as in Cycles' Principled
      // v1 diffuse (no retro-reflection term split off).
      const Vec3 h = normalize(wo + wi);
      const float cos_d = dot(wi, h);
      const float f90 = 0.5f + 2.0f * l.roughness * cos_d * cos_d;
      const float fl = schlick_weight(wi.z), fv = schlick_weight(wo.z);
      r.f = weight * (kInvPi * (1.0f + (f90 - 1.0f) * fl) * (1.0f + (f90 - 1.0f) * fv));
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    }
    case LobeType::kTranslucent:
      if (!shading_transmit) break;
      r.f = weight * kInvPi;
      r.pdf = cosine_hemisphere_pdf(-wi.z);
      break;
    case LobeType::kOrenNayar: {
      if (!shading_reflect) break;
      r.f = weight * oren_nayar(l, tint, wo, wi);
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    }
    case LobeType::kSheen: {
      if (!shading_reflect) break;
      const Vec3 h = normalize(wo + wi);
      r.f = weight * schlick_weight(dot(wi, h));
      r.pdf = cosine_hemisphere_pdf(wi.z);
      break;
    }
    case LobeType::kVelvet:
      if (!shading_reflect) break;
      r.f = weight * velvet(l.roughness, wo, wi);
      r.pdf = wi.z > 0.0f ? 0.5f * kInvPi : 0.0f;
      break;
    case LobeType::kGgxReflection:
      if (shading_reflect) r = ggx_reflection(l, weight, f0, tint, wo, wi, eta);
      break;
    case LobeType::kGgxDielectric:
      if (shading_reflect || shading_transmit) r = ggx_dielectric(l, weight, f0, tint, wo, wi, eta);
      break;
    case LobeType::kGgxGlass:
      if (shading_reflect) r = ggx_reflection(l, weight, f0, tint, wo, wi, eta);
      if (shading_transmit) r = ggx_transmission(l, weight, wo, wi, eta);
      break;
    case LobeType::kGgxRefraction:
      if (shading_transmit) r = ggx_transmission(l, weight, wo, wi, eta);
      break;
    case LobeType::kTransparent:
      break;
  }
  return r;
}

// Samples a direction from one non-delta lobe (local frame, wo.z > 0) and says whether it is a
// reflection. `u_choice` picks reflection or transmission for glass. Returns false when no
// direction comes out (refraction lobe at total internal reflection).
inline bool sample_lobe(const Lobe& l, const Vec3& wo, float eta, float u_choice, Vec2 u, Vec3* wi,
                        bool* reflection) {
  *reflection = true;
  switch (l.type) {
    case LobeType::kLambert:
    case LobeType::kBurleyDiffuse:
    case LobeType::kOrenNayar:
    case LobeType::kSheen:
      *wi = sample_cosine_hemisphere(u);
      return true;
    case LobeType::kTranslucent:
      *wi = -sample_cosine_hemisphere(u);
      *reflection = false;
      return true;
    case LobeType::kVelvet: {
      // Uniform over the hemisphere (pdf 1 / 2 pi), as Cycles samples its velvet.
      const float r = std::sqrt(std::max(0.0f, 1.0f - u.x * u.x));
      const float phi = 2.0f * kPi * u.y;
      *wi = Vec3(r * std::cos(phi), r * std::sin(phi), u.x);
      return true;
    }
    case LobeType::kGgxReflection: {
      const Vec3 h = lobe_sample_visible_normal(l, wo, u);
      *wi = reflect(wo, h);
      return true;
    }
    case LobeType::kGgxGlass:
    case LobeType::kGgxRefraction: {
      const Vec3 h = lobe_sample_visible_normal(l, wo, u);
      const float f = l.type == LobeType::kGgxGlass ? glass_fresnel(wo, eta) : 0.0f;
      if (u_choice < f) {
        *wi = reflect(wo, h);
        return true;
      }
      *reflection = false;
      return refract(wo, h, eta, wi);
    }
    case LobeType::kGgxDielectric: {
      const Vec3 h = lobe_sample_visible_normal(l, wo, u);
      if (u_choice < dielectric_reflect_probability(l, dot(wo, h), eta)) {
        *wi = reflect(wo, h);
        return true;
      }
      *reflection = false;
      return refract(wo, h, eta, wi);
    }
    case LobeType::kTransparent:
      return false;
  }
  return false;
}

template <class C>
struct DeltaSample {
  Vec3 wi;
  C f{0.0f};          // throughput f |cos| integrated over the delta, for this event
  float prob = 1.0f;  // probability of this event within the lobe
  uint8_t flags = 0;
};

// Samples a delta lobe (local frame, wo.z > 0).
template <class C>
bool sample_delta_lobe(const Lobe& l, const C& weight, const C& f0, const C& tint, const Vec3& wo,
                       float eta, float u_choice, DeltaSample<C>* s) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  switch (l.type) {
    case LobeType::kGgxReflection:
      s->wi = reflect(wo, n);
      s->f = weight * reflection_fresnel(l, f0, wo.z, eta, tint);
      s->flags = kLobeReflection | kLobeSpecular;
      return true;
    case LobeType::kGgxDielectric: {
      C r, t;
      dielectric_split(l, f0, tint, wo.z, eta, &r, &t);
      const float pr = dielectric_reflect_probability(l, wo.z, eta);
      if (u_choice < pr) {
        s->wi = reflect(wo, n);
        s->f = weight * r;
        s->prob = pr;
        s->flags = kLobeReflection | kLobeSpecular;
        return true;
      }
      if (!refract(wo, n, eta, &s->wi)) return false;
      s->f = weight * t;
      s->prob = 1.0f - pr;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    }
    case LobeType::kGgxGlass: {
      const float f = fresnel_dielectric(wo.z, eta);  // 1 on total internal reflection
      if (u_choice < f) {
        s->wi = reflect(wo, n);
        s->f = weight * f;
        s->prob = f;
        s->flags = kLobeReflection | kLobeSpecular;
        return true;
      }
      if (!refract(wo, n, eta, &s->wi)) return false;
      s->f = weight * (1.0f - f);
      s->prob = 1.0f - f;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    }
    case LobeType::kGgxRefraction:
      if (!refract(wo, n, eta, &s->wi)) return false;
      s->f = weight;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    case LobeType::kTransparent:
      s->wi = -wo;
      s->f = weight;
      s->flags = kLobeTransmission | kLobeSpecular;
      return true;
    default:
      return false;
  }
}

// The albedo estimate of one lobe at wo (local), used for lobe selection.
inline Vec3 lobe_albedo(const Lobe& l, const Vec3& wo, float eta) {
  if (l.type == LobeType::kGgxReflection)
    return l.weight * reflection_fresnel(l, l.f0, wo.z, eta, l.tint);
  // Sheen grows towards grazing; Cycles picks it by (1 - cos_o)^5 (its avg_value). A floor
  // keeps it selectable at normal incidence, where it still reflects light.
  if (l.type == LobeType::kSheen) return l.weight * std::max(schlick_weight(wo.z), 0.02f);
  return l.weight;
}

}  // namespace photon::bsdf_lobes

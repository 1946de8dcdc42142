// The quantities behind Cycles 4's GGX energy tables, computed here from their definitions (not
// copied): directional albedos of the GGX microfacet reflection and of the GGX dielectric
// interface, and the effective interpolation factor of the "real Fresnel remapped to F0..F90"
// Fresnel model over a rough reflection. Cycles 4's Multiscatter GGX (Principled BSDF v2, Glossy,
// Glass) scales single-scattering lobes by 1 / E(mu) ("albedo scaling", Kulla & Conty 2017), and
// the Principled v2 layers attenuate what lies below by the albedo of the layer above.
//
// Every quantity is an expectation over visible normals h ~ D_wo(h) (Heitz 2018) with wo at
// cos(theta) = mu in the x-z plane, as Cycles' precomputation samples it:
//   E_refl(r, mu)          = E[ G2(wo, wi) / G1(wo) ; wi = reflect(wo, h) above the surface ]
//   E_glass(r, mu, eta)    = E[ F(wo.h) E_refl-term + (1 - F(wo.h)) G2 / G1 ; wi = refract ]
//   s_ior(r, mu, eta)      = E[ s(wo.h) ; reflection above the surface ],
//                            s = clamp((F(wo.h, eta) - F0(eta)) / (1 - F0(eta)), 0, 1)
// with GGX alpha = r^2, the height-correlated Smith G2 = 1 / (1 + L(wo) + L(wi)) and the exact
// dielectric Fresnel F. Averages over the hemisphere weight by 2 mu.
//
// The integrals use a deterministic stratified grid of n x n visible-normal samples (midpoints),
// so the tables are reproducible to the bit. Header-only: the table generator
// (native/tools/microfacet_albedo_gen.cpp) and the unit tests both include it.
#pragma once

#include <algorithm>
#include <cmath>

#include "photon/base/microfacet.h"
#include "photon/base/optics.h"

namespace photon::microfacet_albedo {

// Below this alpha_x * alpha_y a GGX lobe is a perfect mirror / interface in Cycles
// (BSDF_ROUGHNESS_SQ_THRESH): its albedo terms are those of the smooth surface.
constexpr float kSingularAlpha2 = 2e-10f;

inline float f0_from_ior(float ior) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// The IOR whose normal-incidence reflectance is f0 (f0 limited to 0.99, as Cycles limits it).
inline float ior_from_f0(float f0) {
  const float s = std::sqrt(std::clamp(f0, 0.0f, 0.99f));
  return (1.0f + s) / (1.0f - s);
}

// The remap factor of the "real Fresnel to F0..F90" model at microfacet cosine `c`.
inline float schlick_ior_factor(float c, float eta) {
  const float r0 = f0_from_ior(eta);
  const float f = fresnel_dielectric(c, eta);
  if (!(1.0f - r0 > 0.0f)) return 1.0f;
  return std::clamp((f - r0) / (1.0f - r0), 0.0f, 1.0f);
}

// The height-correlated over the one-sided masking term: G2(wo, wi) / G1(wo).
inline float correlated_ratio(float lambda_o, float lambda_i) {
  return (1.0f + lambda_o) / (1.0f + lambda_o + lambda_i);
}

enum class Quantity { kReflection, kGlass, kSchlickIor };

// One directional value of `q` at roughness r (alpha = r^2), cosine mu and relative IOR eta
// (ignored by kReflection), with n x n samples.
inline double directional(Quantity q, float r, float mu, float eta, int n) {
  const float alpha = r * r;
  const Vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  if (alpha * alpha <= kSingularAlpha2) {
    // A smooth surface: the mirror reflection (and refraction) leave with no masking.
    switch (q) {
      case Quantity::kReflection:
      case Quantity::kGlass:
        return 1.0;
      case Quantity::kSchlickIor:
        return schlick_ior_factor(mu, eta);
    }
  }
  const bool unit_eta = std::fabs(eta - 1.0f) < 1e-4f;  // refraction is then a delta event
  const float lambda_o = ggx_lambda(wo, alpha);
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 u((static_cast<float>(i) + 0.5f) / static_cast<float>(n),
                   (static_cast<float>(j) + 0.5f) / static_cast<float>(n));
      const Vec3 h = ggx_sample_visible_normal(wo, alpha, u);
      const float cos_oh = dot(wo, h);
      if (!(cos_oh > 0.0f)) continue;
      const Vec3 wr = reflect(wo, h);
      const float refl = wr.z > 0.0f ? correlated_ratio(lambda_o, ggx_lambda(wr, alpha)) : 0.0f;
      switch (q) {
        case Quantity::kReflection:
          sum += refl;
          break;
        case Quantity::kSchlickIor:
          if (wr.z > 0.0f) sum += schlick_ior_factor(cos_oh, eta);
          break;
        case Quantity::kGlass: {
          const float f = fresnel_dielectric(cos_oh, eta);
          double v = f * refl;
          Vec3 wt;
          if (f < 1.0f && refract(wo, h, eta, &wt) && wt.z < 0.0f)
            v += (1.0f - f) * (unit_eta ? 1.0f : correlated_ratio(lambda_o, ggx_lambda(wt, alpha)));
          sum += v;
          break;
        }
      }
    }
  return sum / (static_cast<double>(n) * n);
}

// The cosine-weighted hemispherical average 2 int_0^1 mu E(mu) dmu, with m cosines (midpoints).
inline double hemispherical(Quantity q, float r, float eta, int m, int n) {
  double sum = 0.0;
  for (int k = 0; k < m; ++k) {
    const float mu = (static_cast<float>(k) + 0.5f) / static_cast<float>(m);
    sum += 2.0 * mu * directional(q, r, mu, eta, n);
  }
  return sum / m;
}

// The tables' grids, as Cycles lays out its own: roughness and cosine at i / (size - 1)
// (clamped away from 0), the IOR axis z at i / (size - 1) in [1e-4, 0.99] with IOR =
// ior_from_f0(z^4) (most resolution for common glasses), read back with z = sqrt((ior - 1) /
// (ior + 1)).
inline float grid_roughness(int i, int size) {
  return std::clamp(static_cast<float>(i) / static_cast<float>(size - 1), 1e-4f, 1.0f);
}
inline float grid_cosine(int i, int size) {
  return std::clamp(static_cast<float>(i) / static_cast<float>(size - 1), 1e-4f, 1.0f);
}
inline float grid_ior(int i, int size) {
  const float z = std::clamp(static_cast<float>(i) / static_cast<float>(size - 1), 1e-4f, 0.99f);
  return ior_from_f0(z * z * z * z);
}

}  // namespace photon::microfacet_albedo

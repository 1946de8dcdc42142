// GGX (Trowbridge-Reitz) microfacet distribution, isotropic and anisotropic, and Schlick's Fresnel.
// Every direction is in the local shading frame (normal +z), unit length, pointing away from the
// surface; `alpha` is the GGX roughness (Blender roughness squared).
#pragma once

#include "photon/base/math.h"

namespace photon {

// Normal distribution D(h) (Walter et al. 2007, eq. 33); 0 for h below the surface.
float ggx_d(const Vec3& h, float alpha);

// Smith's Lambda for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function", eq. 72):
// G1 = 1 / (1 + Lambda).
float ggx_lambda(const Vec3& w, float alpha);

// Smith masking G1(w, h) (Walter 2007, eq. 34), including its chi+(w.h / w.n) factor: 0 when
// `w` sees the back of the microfacet.
float ggx_g1(const Vec3& w, const Vec3& h, float alpha);

// Masking-shadowing G2: the separable form G1(wo, h) G1(wi, h) (Walter 2007, eq. 23), as in
// Cycles 3.4's GGX closures, so renders match it. With visible-normal sampling the sample
// weight of a lobe is then G1(wi) (times Fresnel), never above 1.
float ggx_g2(const Vec3& wo, const Vec3& wi, const Vec3& h, float alpha);

// Samples a microfacet normal from the distribution of normals visible from `wo` (wo.z > 0)
// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1).
Vec3 ggx_sample_visible_normal(const Vec3& wo, float alpha, Vec2 u);

// Density of ggx_sample_visible_normal over the solid angle of h:
// D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018, eq. 2).
float ggx_visible_normal_pdf(const Vec3& wo, const Vec3& h, float alpha);

// Anisotropic GGX, `ax` along the local x axis and `ay` along y (Heitz 2014, eq. 85 for D and
// eq. 86 for Lambda; the visible normals sampled by stretching the view direction with both
// alphas, Heitz 2018, listing 1). With ax == ay they equal the isotropic functions above.
float ggx_d(const Vec3& h, float ax, float ay);
float ggx_lambda(const Vec3& w, float ax, float ay);
float ggx_g1(const Vec3& w, const Vec3& h, float ax, float ay);
Vec3 ggx_sample_visible_normal(const Vec3& wo, float ax, float ay, Vec2 u);
float ggx_visible_normal_pdf(const Vec3& wo, const Vec3& h, float ax, float ay);

// Schlick 1994: F0 + (1 - F0)(1 - cos)^5, per channel.
inline float schlick_weight(float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}
inline Vec3 fresnel_schlick(const Vec3& f0, float cos_theta) {
  return f0 + (Vec3(1.0f) - f0) * schlick_weight(cos_theta);
}

}  // namespace photon

// Beckmann microfacet distribution, isotropic (ax == ay) and anisotropic: Cycles' Beckmann
// option of the Glossy, Anisotropic, Glass and Refraction BSDFs. Directions are in the local
// shading frame (normal +z), unit length; `ax`, `ay` are the roughnesses along x and y (Blender
// roughness squared, as for GGX).
#pragma once

#include "photon/base/math.h"

namespace photon {

// D(h) = exp(-(hx^2/ax^2 + hy^2/ay^2) / hz^2) / (pi ax ay hz^4) (Walter et al. 2007, eq. 25;
// Heitz 2014, eq. 83 for the anisotropic form); 0 for h below the surface.
float beckmann_d(const Vec3& h, float ax, float ay);

// Smith's Lambda in closed form: with a = 1 / (alpha_w tan theta),
// Lambda = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)) (Heitz 2014, eq. 80), alpha_w the
// roughness projected onto w's azimuth (eq. 84). This exact form is what the distribution of
// visible normals below is normalised with.
float beckmann_lambda(const Vec3& w, float ax, float ay);

// Walter et al. 2007's rational approximation of the same Lambda (eq. 27 written as Lambda):
// (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2) for a < 1.6, else 0. Cycles evaluates
// Beckmann's masking with it (3.4 as G1 = 1 / (1 + Lambda), 4.x height-correlated), so lobes
// use it for f to render as Cycles does; it stays within 0.4% of G1 from the exact form.
float beckmann_lambda_approx(const Vec3& w, float ax, float ay);

// Smith masking G1(w, h) = 1 / (1 + beckmann_lambda_approx(w)), 0 when w sees the back of the
// microfacet.
float beckmann_g1(const Vec3& w, const Vec3& h, float ax, float ay);

// Samples a microfacet normal from the distribution of normals visible from `wo` (wo.z > 0):
// stretch wo to unit roughness, draw the slopes of the visible normals there (Heitz & d'Eon
// 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution of Visible Normals":
// the x slope by inverting its cumulative distribution with a safeguarded Newton iteration in
// b = erf(slope), as in Jakob's Mitsuba; the y slope is an independent Gaussian), rotate them to
// wo's azimuth and unstretch.
Vec3 beckmann_sample_visible_normal(const Vec3& wo, float ax, float ay, Vec2 u);

// Density of beckmann_sample_visible_normal over the solid angle of h:
// G1(wo) max(0, wo.h) D(h) / wo.z with the exact Lambda.
float beckmann_visible_normal_pdf(const Vec3& wo, const Vec3& h, float ax, float ay);

// The inverse of the error function on (-1, 1) (Giles 2010, "Approximating the erfinv
// function", the single-precision branch pair; relative error about 4e-7 in float).
float erf_inverse(float x);

}  // namespace photon

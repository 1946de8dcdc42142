// The BSDF at one shading point: a weighted sum of up to kMaxLobes lobes (Lambert, Burley
// diffuse, Oren-Nayar, sheen, translucent, GGX reflection (isotropic or anisotropic) and
// transmission, transparent). A lobe may carry its own shading normal (a clearcoat normal) and
// tangent (anisotropic GGX); the others share the BSDF's frame. The same object serves
// camera paths, photon tracing and final gathering, so what is sampled is what is evaluated.
//
// Conventions (pbrt-v4 style): every direction is in world space, unit length and points away
// from the surface. The shading frame's normal faces `wo`'s side (the caller flips normals of
// back faces); `front_facing` says whether that side is the outward one, which decides the
// relative index of refraction. eval() returns f(wo, wi) without the cosine; sample() returns
// f |cos(theta_i)| / pdf. Radiance is not scaled by 1/eta^2 on refraction (as in Cycles), so
// the BSDF is the same for importance (photons) and radiance (camera paths).
#pragma once

#include <cstdint>

#include "photon/base/math.h"

namespace photon {

enum class LobeType : uint8_t {
  kLambert,        // color / pi
  kBurleyDiffuse,  // Burley 2012 diffuse with `roughness` (Cycles' Principled v1 diffuse)
  kTranslucent,    // color / pi, to the other side
  kGgxReflection,  // GGX microfacet reflection (Walter et al. 2007), Fresnel per `fresnel`
  // Cycles 3.4's Glass BSDF: GGX reflection (F = 1 per microfacet) weighted by the dielectric
  // Fresnel of the shading normal F(wo.z), plus GGX transmission (Walter 2007) weighted by
  // 1 - F(wo.z); not reciprocal, and light refracted into a totally reflecting microfacet is lost.
  kGgxGlass,
  kGgxRefraction,  // GGX transmission only, no Fresnel (Cycles' Refraction BSDF)
  kTransparent,    // straight through, unchanged direction (always a delta lobe)
  // Oren-Nayar 1994 in the qualitative form of Cycles 3.4's bsdf_oren_nayar, sigma = `roughness`
  // (Fujii's "improved Oren-Nayar"); with `oren_nayar_multiscatter` also the energy lost to
  // inter-reflection between the microfacets put back (Cycles 4.3+).
  kOrenNayar,
  // Cycles 3.4 Principled v1 sheen: f = weight (1 - wi.h)^5 (Burley 2012, sec. 5.3), no 1/pi.
  kSheen,
  // Cycles 4's GGX dielectric interface (Principled v2 transmission): one lobe reflecting and
  // refracting per microfacet with the Fresnel of `fresnel` (kSchlickIor: R = mix(f0, 1, s)) at
  // that microfacet, refraction weighted by (1 - R) `tint`; reflection is picked with
  // probability avg(R) / avg(R + T) of the lobe's RGB colours (Walter et al. 2007, eq. 21).
  kGgxDielectric,
  // Cycles' Ashikhmin velvet (Ashikhmin, Premoze & Shirley 2000's fibre distribution
  // D = exp(-cot^2 h / s^2) / (pi s^2 sin^4 h) with s = `roughness`, Cycles' Velvet Sigma, at
  // least 0.01), f = D G / (4 cos_o cos_i) with G = min(1, 2 cos_h cos_o / |wo.h|,
  // 2 cos_h cos_i / |wo.h|): no Fresnel, sampled uniformly over the hemisphere as Cycles does.
  kVelvet,
};

enum class FresnelMode : uint8_t {
  kNone,        // F = 1: the lobe's colour is its reflectance (Cycles' Glossy BSDF)
  kDielectric,  // exact dielectric Fresnel with `ior`
  kSchlick,     // Schlick's approximation with F0 = `f0` (metals, Principled specular)
  // Cycles 3.4's interpolate_fresnel_color (Principled v1 glass reflection): `f0` blended to
  // white by FH = (F(wi.h) - F(1)) / (1 - F(1)), F the dielectric Fresnel with `ior`; white
  // where the microfacet reflects totally.
  kInterpolated,
  // Cycles 4's generalized Schlick in its "real Fresnel" form (Principled v2 specular and
  // transmission): F = mix(f0, 1, s), s = clamp((F_d(cos) - F_d(1)) / (1 - F_d(1)), 0, 1) with
  // F_d the dielectric Fresnel of the lobe's `ior` (white on total internal reflection).
  kSchlickIor,
  // The F82-tint conductor of Kutz et al. 2021 (Principled v2 metallic): Schlick with F0 = `f0`
  // minus b cos (1 - cos)^6, b chosen so that F at cos = 1/7 (about 82 degrees) is Schlick's
  // times `tint`; clamped to [0, 1].
  kF82Tint,
};

// What a lobe does, for choosing which part of the light transport handles it.
enum LobeFlags : uint8_t {
  kLobeReflection = 1u << 0,
  kLobeTransmission = 1u << 1,
  kLobeDiffuse = 1u << 2,   // Lambert and Burley: the photon map's and final gather's part
  kLobeGlossy = 1u << 3,    // rough microfacet and translucent: sampled and ray traced
  kLobeSpecular = 1u << 4,  // delta lobes: sharp reflection / refraction, transparent
  kLobeAll = 0x1F,
};

// Below this GGX alpha a microfacet lobe is a perfect (delta) mirror or interface.
constexpr float kDeltaAlpha = 1e-4f;

struct Lobe {
  LobeType type = LobeType::kLambert;
  Vec3 weight{1.0f};   // closure weight times its colour (tint); never negative
  float alpha = 0.0f;  // GGX alpha = Blender roughness^2 (along the tangent if anisotropic)
  // GGX alpha along the bitangent for an anisotropic lobe; negative: isotropic (= alpha).
  float alpha_y = -1.0f;
  float roughness = 0.0f;  // Burley diffuse roughness / Oren-Nayar sigma (Blender's, not squared)
  float ior = 1.45f;       // kDielectric Fresnel and glass / refraction lobes
  // Abbe number of the lobe's dielectric (0: none): in spectral mode its index of refraction at
  // a wavelength follows Cauchy's law through (ior at the d line, abbe) (spectral/dispersion.h).
  float abbe = 0.0f;
  FresnelMode fresnel = FresnelMode::kNone;
  Vec3 f0{0.04f};  // kSchlick reflectance at normal incidence; kInterpolated's tint
  // The lobe's own shading normal (world space, facing wo's side like the BSDF's), or zero for
  // the BSDF's; one that is not above the geometric surface falls back to the BSDF's.
  Vec3 normal{0.0f};
  // World-space direction of `alpha` for an anisotropic lobe (projected onto the normal's
  // plane), or zero for an arbitrary one.
  Vec3 tangent{0.0f};
  // kF82Tint's edge tint, kGgxDielectric's transmission tint, kOrenNayar's albedo for its
  // multiple scattering term; in [0, 1].
  Vec3 tint{1.0f};
  // The lobe's `ior` holds on both sides of the surface (a layer that only reflects, as Cycles
  // 4's Principled specular and coat): back faces do not invert it.
  bool fixed_ior = false;
  // Height-correlated Smith masking-shadowing G2 = 1 / (1 + L(wo) + L(wi)) (Cycles 4) instead of
  // the separable G1(wo) G1(wi) (Cycles 3.4).
  bool correlated = false;
  // Beckmann's distribution instead of GGX's for the microfacet lobes (with the same alphas).
  bool beckmann = false;
  // kOrenNayar with the multiple scattering term of OpenPBR's energy-preserving Oren-Nayar
  // (Cycles 4.3+'s Diffuse BSDF and Principled Diffuse Roughness).
  bool oren_nayar_multiscatter = false;

  bool anisotropic() const { return alpha_y >= 0.0f; }
  // Whether the lobe's index of refraction depends on the wavelength: an Abbe number and a
  // lobe that reads `ior` (glass, refraction, dielectric or interpolated Fresnel).
  bool dispersive() const;

  uint8_t flags() const;  // LobeFlags of this lobe with its parameters (delta when alpha small)
};

struct BsdfSample {
  Vec3 wi;
  Vec3 weight{0.0f};         // f |cos theta_i| / pdf, over all lobes allowed by the mask
  float pdf = 0.0f;          // solid-angle density; for a delta lobe, its discrete probability
  uint8_t flags = 0;         // LobeFlags of the lobe that was sampled
  bool transparent = false;  // the lobe was a Transparent one (straight through)
  bool is_delta() const { return (flags & kLobeSpecular) != 0; }
};

// The Fresnel factor of a kGgxReflection lobe (its FresnelMode) at the microfacet cosine
// `cos_oh`, with `eta` the relative index of refraction of the side wo is on.
Vec3 lobe_reflection_fresnel(const Lobe& lobe, float cos_oh, float eta);

class SpectralBsdf;

class Bsdf {
 public:
  static constexpr int kMaxLobes = 8;

  Bsdf() = default;
  // `ns`: shading normal, `ng`: geometric normal, both unit length and facing wo's side.
  Bsdf(const Vec3& ns, const Vec3& ng, bool front_facing);

  // Adds a lobe; lobes with a zero weight are dropped, and past kMaxLobes the lightest lobe is.
  void add(const Lobe& lobe);
  int lobe_count() const { return count_; }
  const Lobe& lobe(int i) const { return lobes_[i]; }
  uint8_t flags() const;  // union of the lobes' flags
  bool empty() const { return count_ == 0; }

  // f(wo, wi) summed over the non-delta lobes whose flags intersect `mask`. Reflection and
  // transmission are told apart with the geometric normal (Veach 1997 sec. 5.3), so shading
  // normals do not leak light through a surface.
  Vec3 eval(const Vec3& wo, const Vec3& wi, uint8_t mask = kLobeAll) const;
  // Solid-angle pdf of sample() producing wi, for the same mask (non-delta lobes only; the
  // lobe choice probabilities are included).
  float pdf(const Vec3& wo, const Vec3& wi, uint8_t mask = kLobeAll) const;
  // The density with which sample() from wi's side would produce wo: pdf(wi, wo), with the BSDF
  // seen from behind when wi is on the other side (a transmission), where pdf(wi, wo) is 0.
  // Bidirectional methods weigh their techniques with it (Veach 1997 sec. 10.2).
  float pdf_reverse(const Vec3& wo, const Vec3& wi, uint8_t mask = kLobeAll) const;
  // The same surface with its normals turned to the other side: the BSDF a path that reaches
  // it from behind would shade with (front_facing inverted, so refraction's eta inverts).
  Bsdf seen_from_behind() const;
  // Chooses a lobe among those in `mask` with probability proportional to its estimated albedo
  // at wo (using u_lobe), then samples it with u. For a non-delta lobe, weight and pdf are
  // those of the whole masked mixture (one-sample MIS over lobes). Returns false when nothing
  // can be sampled (wo below the surface, total internal reflection with nothing else, ...).
  bool sample(const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask, BsdfSample* out) const;

  // The colours of the lobes with kLobeDiffuse: their hemispherical reflectance as Lambert
  // lobes (view-independent uses: radiosity, bakes, "is there a diffuse part").
  Vec3 diffuse_reflectance() const;
  // Directional albedo at wo of the lobes with kLobeDiffuse: what turns a photon-map estimate
  // of irradiance (E / pi) into the radiance they reflect towards wo for light arriving evenly
  // over the hemisphere. Exact for Lambert; Burley and Oren-Nayar lobes reflect more or less
  // than their colour depending on wo, and a bumped lobe's shadowing term takes its mean share
  // (separately from the view: approximate for a bumped Burley lobe). Zero when wo cannot be
  // shaded.
  Vec3 diffuse_reflectance(const Vec3& wo) const;
  // An estimate of the directional albedo at wo of the lobes in `mask` (used for choosing
  // lobes and for Russian roulette; exact for Lambert, approximate elsewhere).
  Vec3 albedo(const Vec3& wo, uint8_t mask = kLobeAll) const;

  // The interpolated (smooth) normal, on wo's side: diffuse lobes whose normal (a bump or
  // normal-map normal, the BSDF's or the lobe's own) differs from it are multiplied by the bump
  // shadowing term of Chiang, Li & Burley 2019 ("Taming the Shadow Terminator"), as Cycles
  // does for its diffuse closures.
  void set_smooth_normal(const Vec3& n);

  // What light carried from wo's side to wi's side (a photon, a light subpath) is multiplied by
  // besides f |cos| / pdf. Camera paths see radiance unscaled through a refraction (above, as
  // Cycles), so the adjoint BSDF that carries power the other way holds (n_wo / n_wi)^2 = 1 /
  // eta^2 for a transmission (Veach 1997 sec. 5.2): without it, photons through one refracting
  // surface (a pool's water, a window pane seen from inside) make light eta^2 brighter than
  // camera paths do. 1 for a reflection, and for a surface whose transmission is not one
  // refraction: a Translucent lobe, or refracting lobes of different indices (Transparent lobes,
  // straight through, are the caller's to skip).
  float adjoint_scale(const Vec3& wo, const Vec3& wi) const;

  const Frame& frame() const { return frame_; }
  const Vec3& ng() const { return ng_; }
  bool front_facing() const { return front_facing_; }

 private:
  friend class SpectralBsdf;  // the same lobes at sampled wavelengths (spectral_bsdf.h)
  friend struct BsdfMixture;  // eval, pdf and sample for both colour models (bsdf_mixture.h)
  // Normalises wo and maps it to the shading frame; false when it cannot be shaded (NaN,
  // zero, at or below the shading or geometric horizon, or no lobes).
  bool to_local(const Vec3& wo, Vec3* wo_local, Vec3* wo_world) const;
  // Lobe i's normal: its own frame's, or the BSDF's shading normal.
  const Vec3& lobe_normal(int i) const { return own_frame_[i] ? lobe_frames_[i].n : frame_.n; }
  // Whether lobe i is diffuse and its normal bends from the smooth one, so that it is multiplied
  // by the bump shadowing term.
  bool bump_shadowed(int i) const;
  // The share of diffuse lobe i's reflection its bump shadowing leaves under even lighting
  // (1 for a lobe that is not shadowed).
  float shadowing_mean(int i) const;
  // n_wi / n_wo of a transmission through this surface from wo's side.
  float eta(const Lobe& lobe) const;
  // The lobe that refracts light from wo to wi, when wi is on the other side and the surface
  // has exactly one index of refraction (adjoint_scale); -1 otherwise.
  int refracting_lobe(const Vec3& wo, const Vec3& wi) const;
  // Lobe choice probabilities at wo over the lobes in `mask`; returns how many are non-zero.
  int selection_probabilities(const Vec3& wo_local, uint8_t mask, float* probs) const;

  Frame frame_{Vec3(0.0f, 0.0f, 1.0f)};
  Vec3 ng_{0.0f, 0.0f, 1.0f};
  bool front_facing_ = true;
  bool bumped_ = false;      // smooth_n_ differs from the shading normal
  bool has_smooth_ = false;  // set_smooth_normal was given a normal
  Vec3 smooth_n_{0.0f, 0.0f, 1.0f};
  bool valid_ = true;  // false when constructed without a usable normal: the BSDF is black
  // wo and wi in lobe i's frame, from their world and BSDF-frame forms; false when wo is not
  // above the lobe's own normal.
  bool lobe_local(int i, const Vec3& wo_world, const Vec3& wo, const Vec3& wi_world, const Vec3& wi,
                  Vec3* lwo, Vec3* lwi) const;

  Lobe lobes_[kMaxLobes];
  Frame lobe_frames_[kMaxLobes];  // each lobe's own frame, where own_frame_ says so
  bool own_frame_[kMaxLobes] = {};
  int count_ = 0;
};

}  // namespace photon

// The lobe mixture's evaluation, density and sampling, written once for both colour models (as
// Mitsuba 3 writes its plugins once for RGB and spectral variants): Bsdf sees the lobes in RGB,
// SpectralBsdf at a spectral path's sampled wavelengths, where dispersive lobes have an index of
// refraction per wavelength (spectral_bsdf.h). A colour model `C` provides
//   using Color; using Sample; static constexpr bool kSpectral;
//   const Color& weight(int lobe) const;  const Color& f0(int lobe) const;
//   const Color& tint(int lobe) const;
//   bool dispersive(int lobe) const;  (kSpectral only:) eta(lobe, lane), active lanes.
// Private to render/ (bsdf.cpp, spectral_bsdf.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "photon/render/bsdf.h"
#include "photon/render/bsdf_lobes.h"

namespace photon {

struct BsdfMixture {
  // Sum of f over the masked non-delta lobes and, when `probs` is given, the mixture pdf.
  template <class C>
  static void eval_mixture(const Bsdf& b, const C& c, const Vec3& wo_world, const Vec3& wo,
                           const Vec3& wi_world, const Vec3& wi, uint8_t mask, const float* probs,
                           typename C::Color* f, float* pdf) {
    using namespace bsdf_lobes;
    using Color = typename C::Color;
    *f = Color(0.0f);
    *pdf = 0.0f;
    const bool reflect = dot(wi_world, b.ng_) * dot(wo_world, b.ng_) > 0.0f;
    for (int i = 0; i < b.count_; ++i) {
      const Lobe& l = b.lobes_[i];
      if (!(l.flags() & mask) || is_delta(l)) continue;
      Vec3 lwo, lwi;
      if (!b.lobe_local(i, wo_world, wo, wi_world, wi, &lwo, &lwi)) continue;
      Color fl;
      float pl;
      if constexpr (C::kSpectral) {
        if (c.dispersive(i)) {
          // Each wavelength with its own index; the density is their mean (spectral_bsdf.h).
          fl = Color(0.0f);
          pl = 0.0f;
          for (int k = 0; k < c.active_count(); ++k) {
            const int j = c.active(k);
            const LobeEval<float> e = eval_lobe(l, c.weight(i)[j], c.f0(i)[j], c.tint(i)[j], lwo,
                                                lwi, reflect, c.eta(i, j));
            fl[j] = e.f;
            pl += e.pdf;
          }
          pl /= static_cast<float>(c.active_count());
        } else {
          const LobeEval<Color> e =
              eval_lobe(l, c.weight(i), c.f0(i), c.tint(i), lwo, lwi, reflect, b.eta(l));
          fl = e.f;
          pl = e.pdf;
        }
      } else {
        const LobeEval<Color> e =
            eval_lobe(l, c.weight(i), c.f0(i), c.tint(i), lwo, lwi, reflect, b.eta(l));
        fl = e.f;
        pl = e.pdf;
      }
      // Each diffuse lobe is shadowed by how far its own normal bends from the smooth one.
      *f += b.bump_shadowed(i) ? fl * bump_shadowing(reflect ? b.smooth_n_ : -b.smooth_n_,
                                                     b.lobe_normal(i), wi_world)
                               : fl;
      if (probs) *pdf += probs[i] * pl;
    }
  }

  // Directional albedo at wo of the diffuse lobes (Bsdf::diffuse_reflectance(wo)).
  template <class C>
  static typename C::Color diffuse_reflectance(const Bsdf& b, const C& c, const Vec3& wo) {
    using Color = typename C::Color;
    Color r(0.0f);
    Vec3 wo_l, wo_w;
    if (!b.to_local(wo, &wo_l, &wo_w)) return r;
    for (int i = 0; i < b.count_; ++i) {
      const Lobe& lobe = b.lobes_[i];
      if (!(lobe.flags() & kLobeDiffuse)) continue;
      const float cos_o = b.own_frame_[i] ? b.lobe_frames_[i].to_local(wo_w).z : wo_l.z;
      if (!(cos_o > 1e-7f)) continue;
      r += bsdf_lobes::diffuse_lobe_albedo(lobe, c.weight(i), c.tint(i), cos_o) *
           b.shadowing_mean(i);
    }
    return r;
  }

  template <class C>
  static typename C::Color eval(const Bsdf& b, const C& c, const Vec3& wo, const Vec3& wi,
                                uint8_t mask) {
    using namespace bsdf_lobes;
    using Color = typename C::Color;
    Vec3 wo_l, wo_w;
    if (!b.to_local(wo, &wo_l, &wo_w) || !is_unit_direction(wi)) return Color(0.0f);
    const Vec3 wi_w = unit(wi);
    Color f;
    float pdf;
    eval_mixture(b, c, wo_w, wo_l, wi_w, b.frame_.to_local(wi_w), mask, nullptr, &f, &pdf);
    return is_finite(f) ? f : Color(0.0f);
  }

  template <class C>
  static float pdf(const Bsdf& b, const C& c, const Vec3& wo, const Vec3& wi, uint8_t mask) {
    using namespace bsdf_lobes;
    Vec3 wo_l, wo_w;
    if (!b.to_local(wo, &wo_l, &wo_w) || !is_unit_direction(wi)) return 0.0f;
    float probs[Bsdf::kMaxLobes];
    if (b.selection_probabilities(wo_l, mask, probs) == 0) return 0.0f;
    const Vec3 wi_w = unit(wi);
    typename C::Color f;
    float pdf;
    eval_mixture(b, c, wo_w, wo_l, wi_w, b.frame_.to_local(wi_w), mask, probs, &f, &pdf);
    return std::isfinite(pdf) ? pdf : 0.0f;
  }

  // Chooses a lobe among those in `mask` with probability proportional to its estimated albedo
  // at wo (using u_lobe), then samples it with u (Bsdf::sample).
  template <class C>
  static bool sample(const Bsdf& b, const C& c, const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask,
                     typename C::Sample* out) {
    using namespace bsdf_lobes;
    using Color = typename C::Color;
    Vec3 wo_l, wo_w;
    if (!b.to_local(wo, &wo_l, &wo_w)) return false;
    if (!std::isfinite(u_lobe) || !std::isfinite(u.x) || !std::isfinite(u.y)) return false;
    u_lobe = std::clamp(u_lobe, 0.0f, 0.99999994f);
    u = Vec2(std::clamp(u.x, 0.0f, 0.99999994f), std::clamp(u.y, 0.0f, 0.99999994f));
    float probs[Bsdf::kMaxLobes];
    if (b.selection_probabilities(wo_l, mask, probs) == 0) return false;

    // Choose a lobe and remap u_lobe to [0, 1) within its interval for the lobe's own choice.
    int k = -1;
    float cdf = 0.0f;
    for (int i = 0; i < b.count_; ++i) {
      if (probs[i] <= 0.0f) continue;
      k = i;
      if (u_lobe < cdf + probs[i]) break;
      cdf += probs[i];
    }
    float u_choice = std::clamp((u_lobe - cdf) / probs[k], 0.0f, 0.99999994f);
    const Lobe& lobe = b.lobes_[k];
    const float lobe_eta = b.eta(lobe);
    const float wo_ng = dot(wo_w, b.ng_);
    // wo in the chosen lobe's frame (its selection probability is zero when wo is below it).
    const Frame& lobe_frame = b.own_frame_[k] ? b.lobe_frames_[k] : b.frame_;
    const Vec3 lobe_wo = b.own_frame_[k] ? lobe_frame.to_local(wo_w) : wo_l;
    if constexpr (C::kSpectral) out->terminate = false;

    if (is_delta(lobe)) {
      DeltaSample<Color> s;
      if (!C::kSpectral || !c.dispersive(k)) {
        if (!sample_delta_lobe(lobe, c.weight(k), c.f0(k), c.tint(k), lobe_wo, lobe_eta, u_choice,
                               &s))
          return false;
      } else if constexpr (C::kSpectral) {
        if (!sample_dispersive_delta(c, lobe, k, lobe_wo, u_choice, &s, out)) return false;
      }
      const Vec3 wi = normalize(lobe_frame.to_world(s.wi));
      // The geometric normal must agree with the event (Veach 1997, sec. 5.3).
      const bool reflect = dot(wi, b.ng_) * wo_ng > 0.0f;
      if (reflect != ((s.flags & kLobeReflection) != 0)) return false;
      const float pdf = probs[k] * s.prob;
      if (!(pdf > 0.0f)) return false;
      out->wi = wi;
      out->pdf = pdf;
      out->weight = s.f / pdf;
      out->flags = s.flags;
      out->transparent = lobe.type == LobeType::kTransparent;
      return is_finite(out->weight);
    }

    // A rough dispersive lobe samples with the index of one wavelength in use, picked by
    // u_choice (which then picks reflection or refraction in what is left of its interval).
    float sample_eta = lobe_eta;
    if constexpr (C::kSpectral) {
      if (c.dispersive(k)) {
        const float x = u_choice * static_cast<float>(c.active_count());
        const int pick = std::min(static_cast<int>(x), c.active_count() - 1);
        u_choice = std::clamp(x - static_cast<float>(pick), 0.0f, 0.99999994f);
        sample_eta = c.eta(k, c.active(pick));
      }
    }
    Vec3 wi_l;
    bool reflection;
    if (!sample_lobe(lobe, lobe_wo, sample_eta, u_choice, u, &wi_l, &reflection)) return false;
    const Vec3 wi = normalize(lobe_frame.to_world(wi_l));
    wi_l = b.frame_.to_local(wi);
    const Vec3 lobe_wi = b.own_frame_[k] ? lobe_frame.to_local(wi) : wi_l;
    const bool reflect = dot(wi, b.ng_) * wo_ng > 0.0f;
    // An event that ends on the wrong side of the shading or the geometric surface (a
    // microfacet reflection below the horizon, say) is not returned: eval() and pdf() count
    // neither, so sample() follows pdf() exactly. Glass must check the event itself, since a
    // reflection below the surface lands where its own refraction density is not zero.
    if (reflect != reflection || (reflection ? lobe_wi.z <= 0.0f : lobe_wi.z >= 0.0f)) return false;
    if (!(eval_lobe(lobe, c.weight(k), c.f0(k), c.tint(k), lobe_wo, lobe_wi, reflect, sample_eta)
              .pdf > 0.0f))
      return false;
    Color f;
    float pdf;
    eval_mixture(b, c, wo_w, wo_l, wi, wi_l, mask, probs, &f, &pdf);
    if (!(pdf > 0.0f) || !std::isfinite(pdf)) return false;
    out->wi = wi;
    out->pdf = pdf;
    out->weight = f * (std::fabs(wi_l.z) / pdf);
    // The lobe's flags, narrowed to the event that happened (reflection or transmission).
    out->flags = lobe.flags() & ~(reflect ? kLobeTransmission : kLobeReflection);
    out->transparent = false;
    return is_finite(out->weight);
  }

 private:
  // A smooth dispersive interface at the wavelengths: the hero wavelength (lane 0, always in
  // use) decides the event and the direction. A reflection keeps every wavelength, each weighted
  // by its own Fresnel factor over the hero's probability of reflecting; a refraction only the
  // hero's, and the path must terminate the others (Wilkie et al. 2014, sec. 4.3).
  template <class C>
  static bool sample_dispersive_delta(const C& c, const Lobe& lobe, int k, const Vec3& wo,
                                      float u_choice, bsdf_lobes::DeltaSample<typename C::Color>* s,
                                      typename C::Sample* out) {
    using namespace bsdf_lobes;
    DeltaSample<float> hero;
    if (!sample_delta_lobe(lobe, c.weight(k)[0], c.f0(k)[0], c.tint(k)[0], wo, c.eta(k, 0),
                           u_choice, &hero))
      return false;
    s->wi = hero.wi;
    s->prob = hero.prob;
    s->flags = hero.flags;
    s->f = typename C::Color(0.0f);
    if (hero.flags & kLobeReflection) {
      for (int i = 0; i < c.active_count(); ++i) {
        const int j = c.active(i);
        s->f[j] = lobe.type == LobeType::kGgxGlass
                      ? c.weight(k)[j] * fresnel_dielectric(wo.z, c.eta(k, j))
                      : c.weight(k)[j] *
                            reflection_fresnel(lobe, c.f0(k)[j], wo.z, c.eta(k, j), c.tint(k)[j]);
      }
    } else {
      s->f[0] = hero.f;
      out->terminate = c.active_count() > 1;
    }
    return true;
  }
};

}  // namespace photon

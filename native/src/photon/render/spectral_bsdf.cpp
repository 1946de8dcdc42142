#include "photon/render/spectral_bsdf.h"

#include "photon/render/bsdf_lobes.h"
#include "photon/spectral/dispersion.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {

using namespace bsdf_lobes;

namespace {

// The mirror reflection of a delta lobe at one wavelength of index `eta`: glass by the
// dielectric Fresnel factor of wo, a reflection lobe by its own Fresnel mode.
float delta_reflection(const Lobe& l, float weight, float f0, const Vec3& wo, float eta) {
  if (l.type == LobeType::kGgxGlass) return weight * fresnel_dielectric(wo.z, eta);
  return weight * reflection_fresnel(l, f0, wo.z, eta);
}

}  // namespace

SpectralBsdf::SpectralBsdf(const Bsdf& bsdf, const SampledWavelengths& wl) : bsdf_(&bsdf), wl_(wl) {
  for (int j = 0; j < kSpectrumSamples; ++j)
    if (wl.active(j)) active_[active_count_++] = j;
  for (int i = 0; i < bsdf.count_; ++i) {
    const Lobe& l = bsdf.lobes_[i];
    weight_[i] = spectral::reflectance_at(l.weight, wl);
    if (l.fresnel == FresnelMode::kSchlick || l.fresnel == FresnelMode::kInterpolated)
      f0_[i] = spectral::reflectance_at(l.f0, wl);
    dispersive_[i] = l.dispersive();
    if (!dispersive_[i]) continue;
    const spectral::CauchyDispersion cauchy = spectral::CauchyDispersion::from_abbe(l.ior, l.abbe);
    for (int j = 0; j < kSpectrumSamples; ++j) {
      const float n = std::clamp(cauchy.ior(wl.lambda(j)), 1e-3f, 1e3f);
      eta_[i][j] = bsdf.front_facing_ ? n : 1.0f / n;
    }
  }
}

void SpectralBsdf::eval_mixture(const Vec3& wo_world, const Vec3& wo, const Vec3& wi_world,
                                const Vec3& wi, uint8_t mask, const float* probs,
                                SampledSpectrum* f, float* pdf) const {
  const Bsdf& b = *bsdf_;
  *f = SampledSpectrum(0.0f);
  *pdf = 0.0f;
  const bool reflect = dot(wi_world, b.ng_) * dot(wo_world, b.ng_) > 0.0f;
  for (int i = 0; i < b.count_; ++i) {
    const Lobe& l = b.lobes_[i];
    if (!(l.flags() & mask) || is_delta(l)) continue;
    Vec3 lwo, lwi;
    if (!b.lobe_local(i, wo_world, wo, wi_world, wi, &lwo, &lwi)) continue;
    SampledSpectrum fl(0.0f);
    float pl = 0.0f;
    if (dispersive_[i]) {
      // Each wavelength with its own index; the density is their mean (see the header).
      for (int k = 0; k < active_count_; ++k) {
        const int j = active_[k];
        const LobeEval<float> e =
            eval_lobe(l, weight_[i][j], f0_[i][j], lwo, lwi, reflect, eta_[i][j]);
        fl[j] = e.f;
        pl += e.pdf;
      }
      pl /= static_cast<float>(active_count_);
    } else {
      const LobeEval<SampledSpectrum> e =
          eval_lobe(l, weight_[i], f0_[i], lwo, lwi, reflect, b.eta(l));
      fl = e.f;
      pl = e.pdf;
    }
    // Each diffuse lobe is shadowed by how far its own normal bends from the smooth one.
    const Vec3& ln = b.own_frame_[i] ? b.lobe_frames_[i].n : b.frame_.n;
    const bool shadowed =
        is_diffuse_type(l) &&
        (b.own_frame_[i] ? b.has_smooth_ && length_squared(b.smooth_n_ - ln) > 0.0f : b.bumped_);
    *f += shadowed ? fl * bump_shadowing(reflect ? b.smooth_n_ : -b.smooth_n_, ln, wi_world) : fl;
    if (probs) *pdf += probs[i] * pl;
  }
}

SampledSpectrum SpectralBsdf::eval(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  Vec3 wo_l, wo_w;
  if (!bsdf_ || !bsdf_->to_local(wo, &wo_l, &wo_w) || !is_unit_direction(wi))
    return SampledSpectrum(0.0f);
  const Vec3 wi_w = unit(wi);
  SampledSpectrum f;
  float pdf;
  eval_mixture(wo_w, wo_l, wi_w, bsdf_->frame_.to_local(wi_w), mask, nullptr, &f, &pdf);
  return f.is_finite() ? f : SampledSpectrum(0.0f);
}

float SpectralBsdf::pdf(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  Vec3 wo_l, wo_w;
  if (!bsdf_ || !bsdf_->to_local(wo, &wo_l, &wo_w) || !is_unit_direction(wi)) return 0.0f;
  float probs[Bsdf::kMaxLobes];
  if (bsdf_->selection_probabilities(wo_l, mask, probs) == 0) return 0.0f;
  const Vec3 wi_w = unit(wi);
  SampledSpectrum f;
  float pdf;
  eval_mixture(wo_w, wo_l, wi_w, bsdf_->frame_.to_local(wi_w), mask, probs, &f, &pdf);
  return std::isfinite(pdf) ? pdf : 0.0f;
}

bool SpectralBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask,
                          SpectralBsdfSample* out) const {
  if (!bsdf_) return false;
  const Bsdf& b = *bsdf_;
  Vec3 wo_l, wo_w;
  if (!b.to_local(wo, &wo_l, &wo_w)) return false;
  if (!std::isfinite(u_lobe) || !std::isfinite(u.x) || !std::isfinite(u.y)) return false;
  u_lobe = std::clamp(u_lobe, 0.0f, 0.99999994f);
  u = Vec2(std::clamp(u.x, 0.0f, 0.99999994f), std::clamp(u.y, 0.0f, 0.99999994f));
  float probs[Bsdf::kMaxLobes];
  if (b.selection_probabilities(wo_l, mask, probs) == 0) return false;

  // The lobe, as Bsdf::sample chooses it.
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
  const Frame& lobe_frame = b.own_frame_[k] ? b.lobe_frames_[k] : b.frame_;
  const Vec3 lobe_wo = b.own_frame_[k] ? lobe_frame.to_local(wo_w) : wo_l;
  out->terminate = false;

  if (is_delta(lobe)) {
    DeltaSample<SampledSpectrum> s;
    if (!dispersive_[k]) {
      if (!sample_delta_lobe(lobe, weight_[k], f0_[k], lobe_wo, lobe_eta, u_choice, &s))
        return false;
    } else {
      // The hero wavelength (lane 0, always in use) decides the event and the direction.
      DeltaSample<float> hero;
      if (!sample_delta_lobe(lobe, weight_[k][0], f0_[k][0], lobe_wo, eta_[k][0], u_choice, &hero))
        return false;
      s.wi = hero.wi;
      s.prob = hero.prob;
      s.flags = hero.flags;
      s.f = SampledSpectrum(0.0f);
      if (hero.flags & kLobeReflection) {
        // The mirror direction is every wavelength's; each keeps its own Fresnel factor.
        for (int i = 0; i < active_count_; ++i) {
          const int j = active_[i];
          s.f[j] = delta_reflection(lobe, weight_[k][j], f0_[k][j], lobe_wo, eta_[k][j]);
        }
      } else {
        s.f[0] = hero.f;
        out->terminate = active_count_ > 1;
      }
    }
    const Vec3 wi = normalize(lobe_frame.to_world(s.wi));
    const bool reflect = dot(wi, b.ng_) * wo_ng > 0.0f;
    if (reflect != ((s.flags & kLobeReflection) != 0)) return false;
    const float pdf = probs[k] * s.prob;
    if (!(pdf > 0.0f)) return false;
    out->wi = wi;
    out->pdf = pdf;
    out->weight = s.f / pdf;
    out->flags = s.flags;
    out->transparent = lobe.type == LobeType::kTransparent;
    return out->weight.is_finite();
  }

  // A rough dispersive lobe samples with the index of one wavelength in use, picked by u_choice
  // (which then picks reflection or refraction in what is left of its interval).
  float sample_eta = lobe_eta;
  if (dispersive_[k]) {
    const float x = u_choice * static_cast<float>(active_count_);
    const int pick = std::min(static_cast<int>(x), active_count_ - 1);
    u_choice = std::clamp(x - static_cast<float>(pick), 0.0f, 0.99999994f);
    sample_eta = eta_[k][active_[pick]];
  }
  Vec3 wi_l;
  bool reflection;
  if (!sample_lobe(lobe, lobe_wo, sample_eta, u_choice, u, &wi_l, &reflection)) return false;
  const Vec3 wi = normalize(lobe_frame.to_world(wi_l));
  wi_l = b.frame_.to_local(wi);
  const Vec3 lobe_wi = b.own_frame_[k] ? lobe_frame.to_local(wi) : wi_l;
  const bool reflect = dot(wi, b.ng_) * wo_ng > 0.0f;
  if (reflect != reflection || (reflection ? lobe_wi.z <= 0.0f : lobe_wi.z >= 0.0f)) return false;
  if (!(eval_lobe(lobe, 1.0f, 1.0f, lobe_wo, lobe_wi, reflect, sample_eta).pdf > 0.0f))
    return false;
  SampledSpectrum f;
  float pdf;
  eval_mixture(wo_w, wo_l, wi, wi_l, mask, probs, &f, &pdf);
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return false;
  out->wi = wi;
  out->pdf = pdf;
  out->weight = f * (std::fabs(wi_l.z) / pdf);
  out->flags = lobe.flags() & ~(reflect ? kLobeTransmission : kLobeReflection);
  out->transparent = false;
  return out->weight.is_finite();
}

SampledSpectrum SpectralBsdf::diffuse_reflectance() const {
  SampledSpectrum r(0.0f);
  if (!bsdf_) return r;
  for (int i = 0; i < bsdf_->count_; ++i)
    if (bsdf_->lobes_[i].flags() & kLobeDiffuse) r += weight_[i];
  return r;
}

}  // namespace photon

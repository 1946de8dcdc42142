#include "photon/render/spectral_bsdf.h"

#include "photon/render/bsdf_lobes.h"
#include "photon/render/bsdf_mixture.h"
#include "photon/spectral/dispersion.h"
#include "photon/spectral/rgb_uplift.h"

namespace photon {

using namespace bsdf_lobes;

SpectralBsdf::SpectralBsdf(const Bsdf& bsdf, const SampledWavelengths& wl) : bsdf_(&bsdf), wl_(wl) {
  for (int j = 0; j < kSpectrumSamples; ++j)
    if (wl.active(j)) active_[active_count_++] = j;
  for (int i = 0; i < bsdf.count_; ++i) {
    const Lobe& l = bsdf.lobes_[i];
    weight_[i] = spectral::reflectance_at(l.weight, wl);
    if (l.fresnel == FresnelMode::kSchlick || l.fresnel == FresnelMode::kInterpolated ||
        l.fresnel == FresnelMode::kSchlickIor || l.fresnel == FresnelMode::kF82Tint)
      f0_[i] = spectral::reflectance_at(l.f0, wl);
    if (l.fresnel == FresnelMode::kF82Tint || l.type == LobeType::kGgxDielectric)
      tint_[i] = spectral::reflectance_at(l.tint, wl);
    dispersive_[i] = l.dispersive();
    if (!dispersive_[i]) continue;
    const spectral::CauchyDispersion cauchy = spectral::CauchyDispersion::from_abbe(l.ior, l.abbe);
    for (int j = 0; j < kSpectrumSamples; ++j) {
      const float n = std::clamp(cauchy.ior(wl.lambda(j)), 1e-3f, 1e3f);
      eta_[i][j] = bsdf.front_facing_ ? n : 1.0f / n;
    }
  }
}

SampledSpectrum SpectralBsdf::eval(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  return bsdf_ ? BsdfMixture::eval(*bsdf_, *this, wo, wi, mask) : SampledSpectrum(0.0f);
}

float SpectralBsdf::pdf(const Vec3& wo, const Vec3& wi, uint8_t mask) const {
  return bsdf_ ? BsdfMixture::pdf(*bsdf_, *this, wo, wi, mask) : 0.0f;
}

bool SpectralBsdf::sample(const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask,
                          SpectralBsdfSample* out) const {
  return bsdf_ && BsdfMixture::sample(*bsdf_, *this, wo, u_lobe, u, mask, out);
}

SampledSpectrum SpectralBsdf::adjoint_scale(const Vec3& wo, const Vec3& wi) const {
  if (!bsdf_) return SampledSpectrum(1.0f);
  const int i = bsdf_->refracting_lobe(wo, wi);
  if (i < 0 || !dispersive_[i]) return SampledSpectrum(bsdf_->adjoint_scale(wo, wi));
  SampledSpectrum s(1.0f);
  for (int j = 0; j < kSpectrumSamples; ++j) {
    const float e = eta_[i][j];
    if (e > 0.0f && std::isfinite(e)) s[j] = 1.0f / (e * e);
  }
  return s;
}

SampledSpectrum SpectralBsdf::diffuse_reflectance() const {
  SampledSpectrum r(0.0f);
  if (!bsdf_) return r;
  for (int i = 0; i < bsdf_->count_; ++i)
    if (bsdf_->lobes_[i].flags() & kLobeDiffuse) r += weight_[i];
  return r;
}

SampledSpectrum SpectralBsdf::diffuse_reflectance(const Vec3& wo) const {
  if (!bsdf_) return SampledSpectrum(0.0f);
  return BsdfMixture::diffuse_reflectance(*bsdf_, *this, wo);
}

}  // namespace photon

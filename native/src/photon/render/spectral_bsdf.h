// A BSDF at the sampled wavelengths of a spectral path: the lobes of an RGB Bsdf with their
// colours uplifted to spectra once per shading point (Jakob & Hanika 2019: reflectances in
// [0, 1] as RgbAlbedoSpectrum, larger weights as RgbUnboundedSpectrum) and, for dispersive lobes,
// an index of refraction per wavelength (Cauchy's law from the lobe's ior and Abbe number).
//
// Lobes are chosen as the RGB Bsdf chooses them (the same probabilities), so both modes make the
// same choices from the same random numbers. Dispersion:
//  - a smooth dispersive refraction refracts the hero wavelength (lane 0) and says so
//    (`terminate`): the path's other wavelengths end there (Wilkie et al. 2014, sec. 4.3).
//    A reflection off the same interface keeps every wavelength, each weighted by its own Fresnel
//    factor over the hero's probability of reflecting.
//  - a rough dispersive lobe samples its microfacet refraction with the index of one wavelength
//    picked uniformly among those in use, so its direction density is the mean of the
//    wavelengths' densities, and wavelength i gets f_i |cos| / mean_j pdf_j: the balance
//    heuristic over the wavelengths as sampling techniques (one-sample MIS, Veach 1997
//    sec. 9.2.4). pdf() returns that mean, so light sampling is weighed against the same
//    density whichever wavelength sampled.
#pragma once

#include "photon/render/bsdf.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon {

using spectral::kSpectrumSamples;

struct SpectralBsdfSample {
  Vec3 wi;
  SampledSpectrum weight;  // f |cos theta_i| / pdf at each wavelength
  float pdf = 0.0f;        // as BsdfSample::pdf
  uint8_t flags = 0;       // LobeFlags of the sampled lobe
  bool transparent = false;
  // A dispersive delta refraction: wi is the hero wavelength's direction, every other
  // wavelength's weight is 0 and the path must terminate them (SampledWavelengths).
  bool terminate = false;
  bool is_delta() const { return (flags & kLobeSpecular) != 0; }
};

class SpectralBsdf {
 public:
  SpectralBsdf() = default;
  // `bsdf` must outlive this object; `wl` is copied.
  SpectralBsdf(const Bsdf& bsdf, const SampledWavelengths& wl);

  const Bsdf& rgb() const { return *bsdf_; }
  const SampledWavelengths& wavelengths() const { return wl_; }
  uint8_t flags() const { return bsdf_->flags(); }
  bool empty() const { return bsdf_->empty(); }
  const Frame& frame() const { return bsdf_->frame(); }
  const Vec3& ng() const { return bsdf_->ng(); }

  // As Bsdf::eval, Bsdf::pdf and Bsdf::sample, at the wavelengths.
  SampledSpectrum eval(const Vec3& wo, const Vec3& wi, uint8_t mask = kLobeAll) const;
  float pdf(const Vec3& wo, const Vec3& wi, uint8_t mask = kLobeAll) const;
  bool sample(const Vec3& wo, float u_lobe, Vec2 u, uint8_t mask, SpectralBsdfSample* out) const;
  // Bsdf::adjoint_scale at each wavelength: a dispersive refraction's index is the wavelength's.
  SampledSpectrum adjoint_scale(const Vec3& wo, const Vec3& wi) const;
  // Hemispherical reflectance of the diffuse lobes at the wavelengths.
  SampledSpectrum diffuse_reflectance() const;
  // Directional albedo at wo of the diffuse lobes at the wavelengths (Bsdf::diffuse_reflectance).
  SampledSpectrum diffuse_reflectance(const Vec3& wo) const;

  // Its colour model for the lobe mixture (bsdf_mixture.h): the lobes' colours uplifted at the
  // wavelengths, and the dispersive lobes' indices per wavelength.
  using Color = SampledSpectrum;
  using Sample = SpectralBsdfSample;
  static constexpr bool kSpectral = true;
  const SampledSpectrum& weight(int lobe) const { return weight_[lobe]; }
  const SampledSpectrum& f0(int lobe) const { return f0_[lobe]; }
  const SampledSpectrum& tint(int lobe) const { return tint_[lobe]; }
  bool dispersive(int lobe) const { return dispersive_[lobe]; }
  float eta(int lobe, int lane) const { return eta_[lobe][lane]; }
  int active_count() const { return active_count_; }
  int active(int k) const { return active_[k]; }

 private:
  const Bsdf* bsdf_ = nullptr;
  SampledWavelengths wl_;
  SampledSpectrum weight_[Bsdf::kMaxLobes];
  SampledSpectrum f0_[Bsdf::kMaxLobes];
  SampledSpectrum tint_[Bsdf::kMaxLobes];  // kF82Tint / kGgxDielectric tints
  // Relative index of refraction (as Bsdf::eta) per wavelength of the dispersive lobes.
  float eta_[Bsdf::kMaxLobes][kSpectrumSamples] = {};
  bool dispersive_[Bsdf::kMaxLobes] = {};
  int active_[kSpectrumSamples] = {};  // the wavelengths in use (pdf > 0), lane 0 first
  int active_count_ = 0;
};

}  // namespace photon

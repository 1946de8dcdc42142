// Spectral rendering's side of a path: whether a render is spectral, the wavelengths of a
// camera sample, and the light a path gathers at them, turned into the scene-linear Rec.709
// that the image and its passes hold (CIE 1931 XYZ, then the XYZ -> Rec.709 matrix).
//
// Wavelengths: hero-wavelength sampling (Wilkie et al. 2014) with the visible-response density,
// `spectral_samples` of the kSpectrumSamples lanes in use, from a number stratified over the
// pixel's samples that takes no sampler dimension, so every other random number of a spectral
// render is the RGB render's.
#pragma once

#include "photon/base/rng.h"
#include "photon/integrators/integrator.h"
#include "photon/integrators/registry.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon {

// Whether paths carry wavelengths: with the setting on, for integrators that render spectrally
// (radiosity renders in RGB whatever the setting: its patches store RGB radiosity; the sessions
// say so when they sanitize the settings).
inline bool spectral_mode(const RenderSettings& s) {
  return s.spectral && integrator_info(s.integrator).capabilities.spectral;
}
inline bool spectral_mode(const RenderContext& context) {
  return context.settings && spectral_mode(*context.settings);
}

// The tag of Sampler::stratified_1d that camera samples draw their wavelengths from.
constexpr uint64_t kWavelengthTag = 0x5741564Cull;  // "WAVL"

// The wavelengths of one camera sample (or of one iteration, from its own sampler).
SampledWavelengths sample_wavelengths(const RenderSettings& settings, const Sampler& sampler);

// Light a spectral path gathers, kept as L / pdf per wavelength with the pdfs as they were when
// it was added (a later termination changes them), and turned into Rec.709 once at the end.
struct SpectralTally {
  SampledSpectrum sum{0.0f};

  void add(const SampledSpectrum& l, const SampledWavelengths& wl) { sum += l.safe_div(wl.pdf()); }
  // The Monte Carlo XYZ of the sum at wavelengths `wl` (spectral::sampled_to_xyz), in Rec.709.
  Vec3 rgb(const SampledWavelengths& wl) const;
};

// The mean of `s` over the wavelengths in use (alpha and holdouts of a spectral path).
float mean_in_use(const SampledSpectrum& s, const SampledWavelengths& wl);

}  // namespace photon

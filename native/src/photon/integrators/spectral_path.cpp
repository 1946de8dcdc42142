#include "photon/integrators/spectral_path.h"

#include "photon/spectral/colorimetry.h"

namespace photon {

SampledWavelengths sample_wavelengths(const RenderSettings& settings, const Sampler& sampler) {
  return SampledWavelengths::sample_visible(sampler.stratified_1d(kWavelengthTag),
                                            settings.spectral_samples);
}

Vec3 SpectralTally::rgb(const SampledWavelengths& wl) const {
  Vec3 xyz(0.0f);
  for (int i = 0; i < spectral::kSpectrumSamples; ++i)
    if (sum[i] != 0.0f) xyz += spectral::cie_xyz(wl.lambda(i)) * sum[i];
  xyz = xyz / (static_cast<float>(spectral::kSpectrumSamples) * spectral::cie_y_integral());
  return spectral::xyz_to_rec709(xyz);
}

float mean_in_use(const SampledSpectrum& s, const SampledWavelengths& wl) {
  float sum = 0.0f;
  int n = 0;
  for (int i = 0; i < spectral::kSpectrumSamples; ++i)
    if (wl.active(i)) sum += s[i], ++n;
  return n ? sum / static_cast<float>(n) : 0.0f;
}

}  // namespace photon

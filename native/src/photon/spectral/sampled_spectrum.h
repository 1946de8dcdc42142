// What a spectral path carries: N wavelengths with their sampling densities
// (SampledWavelengths) and N values at those wavelengths (SampledSpectrum). Hero-wavelength
// sampling after Wilkie et al. 2014, "Hero Wavelength Spectral Sampling" (EGSR): one uniform
// number picks the hero wavelength, the other N-1 are rotations of it by multiples of range/N
// (Eq. 4), so the N wavelengths are stratified over the range and share one path.
#pragma once

#include <array>
#include <cmath>

#include "photon/spectral/cie.h"

namespace photon::spectral {

// Wavelengths per path: 4 fills one SSE register and is what Wilkie et al. measure as the
// knee of the noise/cost curve.
constexpr int kSpectrumSamples = 4;

class SampledSpectrum {
 public:
  SampledSpectrum() = default;
  explicit SampledSpectrum(float c) { values_.fill(c); }

  float operator[](int i) const { return values_[i]; }
  float& operator[](int i) { return values_[i]; }

#define PHOTON_SPECTRUM_OP(op)                                                 \
  SampledSpectrum& operator op##=(const SampledSpectrum& b) {                  \
    for (int i = 0; i < kSpectrumSamples; ++i) values_[i] op## = b.values_[i]; \
    return *this;                                                              \
  }                                                                            \
  SampledSpectrum operator op(const SampledSpectrum& b) const {                \
    SampledSpectrum r = *this;                                                 \
    return r op## = b;                                                         \
  }                                                                            \
  SampledSpectrum& operator op##=(float s) {                                   \
    for (int i = 0; i < kSpectrumSamples; ++i) values_[i] op## = s;            \
    return *this;                                                              \
  }                                                                            \
  SampledSpectrum operator op(float s) const {                                 \
    SampledSpectrum r = *this;                                                 \
    return r op## = s;                                                         \
  }
  PHOTON_SPECTRUM_OP(+)
  PHOTON_SPECTRUM_OP(-)
  PHOTON_SPECTRUM_OP(*)
#undef PHOTON_SPECTRUM_OP
  SampledSpectrum operator/(float s) const {
    return *this * (1.0f / s);
  }

  // Division that gives 0 where the divisor is 0 (a terminated wavelength has pdf 0).
  SampledSpectrum safe_div(const SampledSpectrum& b) const {
    SampledSpectrum r;
    for (int i = 0; i < kSpectrumSamples; ++i)
      r.values_[i] = b.values_[i] != 0.0f ? values_[i] / b.values_[i] : 0.0f;
    return r;
  }

  bool is_black() const {
    for (float v : values_)
      if (v != 0.0f) return false;
    return true;
  }
  float max_value() const {
    float m = values_[0];
    for (float v : values_) m = std::fmax(m, v);
    return m;
  }
  float average() const {
    float s = 0.0f;
    for (float v : values_) s += v;
    return s / kSpectrumSamples;
  }
  bool is_finite() const {
    for (float v : values_)
      if (!std::isfinite(v)) return false;
    return true;
  }

 private:
  std::array<float, kSpectrumSamples> values_{};
};

inline SampledSpectrum operator*(float s, const SampledSpectrum& v) {
  return v * s;
}

// The Vec3 helpers' counterparts, so colour-generic code reads the same for both types.
inline bool is_black(const SampledSpectrum& s) {
  for (int i = 0; i < kSpectrumSamples; ++i)
    if (s[i] > 0.0f) return false;
  return true;
}
inline bool is_finite(const SampledSpectrum& s) {
  return s.is_finite();
}
inline float max_component(const SampledSpectrum& s) {
  return s.max_value();
}
// Each value clamped to [0, 1] (render/bsdf_lobes.h's Fresnel models).
// `f` applied to each wavelength's value (the BSDF's per-channel formulas).
template <class F>
SampledSpectrum map_channels(SampledSpectrum s, F f) {
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = f(s[i]);
  return s;
}

inline SampledSpectrum saturate_channels(SampledSpectrum s) {
  for (int i = 0; i < kSpectrumSamples; ++i)
    s[i] = s[i] < 0.0f ? 0.0f : (s[i] > 1.0f ? 1.0f : s[i]);
  return s;
}

class SampledWavelengths {
 public:
  // Hero wavelength uniform over [lambda_min, lambda_max] from `u` in [0,1), the others
  // rotated by (lambda_max - lambda_min) / N and wrapped (Wilkie et al. 2014, Eq. 4); every
  // one has pdf 1 / (lambda_max - lambda_min).
  static SampledWavelengths sample_uniform(float u, float lambda_min = kLambdaMin,
                                           float lambda_max = kLambdaMax);
  // Each wavelength drawn from visible_wavelength_pdf by inversion, the N uniform numbers
  // being u + i/N wrapped (stratified), as pbrt-v4's SampleVisible: fewer samples where the
  // eye does not see.
  static SampledWavelengths sample_visible(float u);
  // The same with only the first `n` (1..N) wavelengths in use, u + i/n for i < n: the others
  // get pdf 0, and the used ones pdf times n/N, so the N-sample average of sampled_to_xyz is
  // the n-sample estimator.
  static SampledWavelengths sample_visible(float u, int n);
  // One wavelength `lambda` drawn with density `pdf` (a photon's): lane 0, the others unused.
  static SampledWavelengths single(float lambda, float pdf);

  float lambda(int i) const { return lambda_[i]; }
  float pdf(int i) const { return pdf_[i]; }
  SampledSpectrum pdf() const {
    SampledSpectrum p;
    for (int i = 0; i < kSpectrumSamples; ++i) p[i] = pdf_[i];
    return p;
  }

  // After a wavelength-dependent event (dispersion) only the hero wavelength goes on: the
  // secondaries get pdf 0 (their contributions vanish through safe_div) and the hero's pdf is
  // divided by the number of wavelengths in use, so that their average becomes the one-sample
  // estimator.
  void terminate_secondary();
  bool secondary_terminated() const;
  // Wavelengths in use (pdf > 0), and whether wavelength i is.
  int active_count() const;
  bool active(int i) const { return pdf_[i] > 0.0f; }

 private:
  std::array<float, kSpectrumSamples> lambda_{};
  std::array<float, kSpectrumSamples> pdf_{};
};

// The visible-response sampling density on [360, 830] nm (pbrt-v4, after Radziszewski et al.
// 2009): proportional to 1 / cosh^2(0.0072 (lambda - 538)), normalised on the range.
float visible_wavelength_pdf(float lambda);
// Its inverse CDF: a wavelength in [360, 830] for u in [0, 1].
float sample_visible_wavelength(float u);

}  // namespace photon::spectral

namespace photon {
// The renderer uses these by their short names.
using spectral::SampledSpectrum;
using spectral::SampledWavelengths;
}  // namespace photon

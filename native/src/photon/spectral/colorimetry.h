// Spectra tabulated every 1 nm, their CIE XYZ (exact sums on the table, or the Monte Carlo
// estimate from a path's sampled wavelengths), and the XYZ <-> linear Rec.709 / CIELAB maps.
#pragma once

#include <array>

#include "photon/base/math.h"
#include "photon/spectral/cie.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon::spectral {

// A spectrum tabulated every 1 nm over 360..830 nm (kTableSamples values), linearly
// interpolated between, 0 outside (pbrt-v4's DenselySampledSpectrum).
class TabulatedSpectrum {
 public:
  TabulatedSpectrum() = default;
  // Samples at lambda0 + i * step (i < count) interpolated linearly onto the 1 nm grid; 0
  // outside [lambda0, lambda0 + (count - 1) step].
  static TabulatedSpectrum from_samples(float lambda0, float step, const float* values, int count);
  template <class F>
  static TabulatedSpectrum from_function(F f) {
    TabulatedSpectrum s;
    for (int i = 0; i < kTableSamples; ++i) s.values_[i] = f(kLambdaMin + static_cast<float>(i));
    return s;
  }

  float operator()(float lambda) const;
  SampledSpectrum sample(const SampledWavelengths& wl) const {
    SampledSpectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = (*this)(wl.lambda(i));
    return s;
  }
  float at(int i) const { return values_[i]; }
  void scale(float s) {
    for (float& v : values_) v *= s;
  }

 private:
  std::array<float, kTableSamples> values_{};
};

struct Mat3 {
  double m[3][3];
  Vec3 operator*(const Vec3& v) const {
    return {static_cast<float>(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z),
            static_cast<float>(m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z),
            static_cast<float>(m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z)};
  }
};

// XYZ of an emission spectrum: sum(S xyz) / sum(y) on the 1 nm table, so that an
// equal-energy spectrum of value 1 has Y = 1.
Vec3 emission_to_xyz(const TabulatedSpectrum& s);
// XYZ of a reflectance under an illuminant: sum(R I xyz) / sum(I y), so that R = 1 has Y = 1.
Vec3 reflectance_to_xyz(const TabulatedSpectrum& r, const TabulatedSpectrum& illuminant);
// Monte Carlo estimate of emission_to_xyz from a path's N samples:
// mean_i(L_i xyz(lambda_i) / pdf_i) / sum(y); wavelengths with pdf 0 contribute nothing.
Vec3 sampled_to_xyz(const SampledSpectrum& radiance, const SampledWavelengths& wl);

// Linear Rec.709 (ITU-R BT.709 primaries, D65 white x = 0.3127, y = 0.3290) from and to XYZ,
// derived from the chromaticities (SMPTE RP 177-1993).
const Mat3& xyz_to_rec709_matrix();
const Mat3& rec709_to_xyz_matrix();
inline Vec3 xyz_to_rec709(const Vec3& xyz) {
  return xyz_to_rec709_matrix() * xyz;
}
inline Vec3 rec709_to_xyz(const Vec3& rgb) {
  return rec709_to_xyz_matrix() * rgb;
}

// Linear Rec.709 of a unit of spectral radiance at `lambda` nm: xyz(lambda) / sum(y), so that a
// sample of value L drawn with density pdf adds wavelength_rec709(lambda) L / pdf to a Monte
// Carlo estimate of emission_to_xyz (a photon's share). Tabulated every 1 nm; may be negative
// (spectral colours lie outside the Rec.709 gamut); 0 outside 360..830 nm.
Vec3 wavelength_rec709(float lambda);

// CIE 1976 L*a*b* of `xyz` relative to the reference white `white` (CIE 15:2004, Section 8.2.1).
Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white);

}  // namespace photon::spectral

// RGB -> spectrum uplifting for linear Rec.709 (Jakob & Hanika 2019, "A Low-Dimensional
// Function Space for Efficient Spectral Upsampling"): a reflectance colour becomes the sigmoid
// of a quadratic in wavelength, its 3 coefficients taken from a table fitted at build
// time (uplift_fit.h, native/tools/uplift_table_gen.cpp). The spectrum classes follow pbrt-v4's
// RGBAlbedoSpectrum / RGBUnboundedSpectrum / RGBIlluminantSpectrum.
#pragma once

#include <cmath>

#include "photon/base/math.h"
#include "photon/spectral/colorimetry.h"
#include "photon/spectral/sampled_spectrum.h"

namespace photon::spectral {

// s(lambda) = S(c0 t^2 + c1 t + c2), t = (lambda - 360) / 470, S(x) = 1/2 + x / (2 sqrt(1+x^2)):
// always in [0, 1]; an infinite c2 with c0 = c1 = 0 is the constant 0 or 1.
struct SigmoidPolynomial {
  float c0 = 0.0f, c1 = 0.0f, c2 = 0.0f;

  static float sigmoid(float x) {
    if (std::isinf(x)) return x > 0.0f ? 1.0f : 0.0f;
    return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
  }
  float operator()(float lambda) const {
    if (std::isnan(lambda)) return 0.0f;
    const float t = (lambda - kLambdaMin) * (1.0f / (kLambdaMax - kLambdaMin));
    if (c0 == 0.0f && c1 == 0.0f) return sigmoid(c2);  // constant (the grey axis: c2 may be inf)
    return sigmoid((c0 * t + c1) * t + c2);
  }
  // Largest value over 360..830 nm: at an end or at the vertex of the quadratic.
  float max_value() const;
};

// A reflectance spectrum as the table reconstructs it: the trilinear blend, with weights
// summing to 1, of the fitted spectra of the 8 nodes around the colour. Blending spectra
// instead of coefficients keeps the round trip exact: colour is linear in the spectrum, and
// trilinear interpolation reproduces the nodes' colours (z, x z, y z) exactly, so the blend's
// colour is the input up to the fit residual; each node spectrum is in [0, 1], so is the blend.
// (Interpolating the coefficients, as the paper and pbrt-v4 do, measured up to 2e-2 RGB error
// between nodes at 32^3 and 9e-3 at 64^3, near white and for dark saturated colours.) Node
// layer 0 (black) is the zero spectrum and adds no term. Evaluating costs up to 8 sigmoids.
struct BlendedSigmoids {
  static constexpr int kMaxTerms = 8;
  SigmoidPolynomial term[kMaxTerms];
  float weight[kMaxTerms] = {};
  int count = 0;

  float operator()(float lambda) const {
    float v = 0.0f;
    for (int k = 0; k < count; ++k) v += weight[k] * term[k](lambda);
    return v;
  }
  // All N wavelengths at once: terms outside, wavelengths inside, so the compiler can keep the
  // N lanes in one vector register.
  SampledSpectrum sample(const SampledWavelengths& wl) const;
};

// The fitted coefficients over the RGB cube: for the largest component z and the other two
// divided by it (x, y uniform, z on uplift_z_node), 3 sheets by which component is largest.
class RgbToSpectrumTable {
 public:
  // The table generated at build time for linear Rec.709 under D65.
  static const RgbToSpectrumTable& rec709();

  // The spectrum of `rgb` clamped to [0, 1] (NaN as 0). Equal components give the exact
  // constant (one term, c0 = c1 = 0, S(c2) = the component), so (1,1,1) is 1 and (0,0,0) is 0.
  BlendedSigmoids operator()(const Vec3& rgb) const;

  int resolution() const { return resolution_; }

  RgbToSpectrumTable(int resolution, const float* z_nodes, const float* coeffs)
      : resolution_(resolution), z_nodes_(z_nodes), coeffs_(coeffs) {}

 private:
  struct Cell {
    int sheet, xi, yi, zi;
    float dx, dy, dz;
  };
  // false for the grey axis, whose exact constant `grey` is returned instead.
  bool locate(const Vec3& rgb, Cell* cell, SigmoidPolynomial* grey) const;
  SigmoidPolynomial node(int sheet, int zi, int yi, int xi) const;

  int resolution_;
  const float* z_nodes_;
  const float* coeffs_;
};

// A reflectance (albedo) colour in [0,1]^3 as a spectrum in [0, 1].
class RgbAlbedoSpectrum {
 public:
  RgbAlbedoSpectrum(const RgbToSpectrumTable& table, const Vec3& rgb) : blend_(table(rgb)) {}
  float operator()(float lambda) const { return blend_(lambda); }
  SampledSpectrum sample(const SampledWavelengths& wl) const;

 private:
  BlendedSigmoids blend_;
};

// Any non-negative colour (emission strengths, > 1 allowed): the colour divided by twice its
// largest component is uplifted and the spectrum scaled back (pbrt-v4's RGBUnboundedSpectrum),
// so its shape keeps room on both sides of 1/2.
class RgbUnboundedSpectrum {
 public:
  RgbUnboundedSpectrum(const RgbToSpectrumTable& table, const Vec3& rgb);
  float operator()(float lambda) const { return scale_ * blend_(lambda); }
  SampledSpectrum sample(const SampledWavelengths& wl) const;

 private:
  float scale_ = 0.0f;
  BlendedSigmoids blend_;
};

// A light's colour: the unbounded spectrum times D65 (scaled to luminance 1), so that RGB
// (1,1,1) is D65 itself, white in Rec.709, and its XYZ maps back to the RGB it came from.
class RgbIlluminantSpectrum {
 public:
  RgbIlluminantSpectrum(const RgbToSpectrumTable& table, const Vec3& rgb);
  float operator()(float lambda) const;
  SampledSpectrum sample(const SampledWavelengths& wl) const;

 private:
  RgbUnboundedSpectrum unbounded_;
  const TabulatedSpectrum* illuminant_;
};

// A reflectance or weight colour as a spectrum: RgbAlbedoSpectrum within [0, 1], else
// RgbUnboundedSpectrum (Add Shader sums above 1); grey is exactly its value everywhere.
class ReflectanceSpectrum {
 public:
  explicit ReflectanceSpectrum(const Vec3& rgb);
  float operator()(float lambda) const { return grey_ ? scale_ : scale_ * blend_(lambda); }
  SampledSpectrum sample(const SampledWavelengths& wl) const {
    return grey_ ? SampledSpectrum(scale_) : blend_.sample(wl) * scale_;
  }

 private:
  BlendedSigmoids blend_;
  float scale_ = 0.0f;
  bool grey_ = true;
};

inline SampledSpectrum reflectance_at(const Vec3& rgb, const SampledWavelengths& wl) {
  return ReflectanceSpectrum(rgb).sample(wl);
}
// An emitted colour (radiance, intensity, flux) at the wavelengths: RgbIlluminantSpectrum, so
// white is D65. Homogeneous: illuminant_at(k c) = k illuminant_at(c) for k >= 0.
SampledSpectrum illuminant_at(const Vec3& rgb, const SampledWavelengths& wl);

}  // namespace photon::spectral

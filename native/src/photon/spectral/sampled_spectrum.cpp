#include "photon/spectral/sampled_spectrum.h"

#include <algorithm>

namespace photon::spectral {
namespace {

// visible_wavelength_pdf(lambda) = k / cosh^2(a (lambda - c)); its CDF is
// (tanh(a (lambda - c)) - tanh(a (360 - c))) / (tanh(a (830 - c)) - tanh(a (360 - c))).
constexpr double kVisA = 0.0072;
constexpr double kVisCenter = 538.0;

double tanh_at(double lambda) {
  return std::tanh(kVisA * (lambda - kVisCenter));
}

float wrap01(float u) {
  return u - std::floor(u);
}

}  // namespace

float visible_wavelength_pdf(float lambda) {
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0.0f;
  static const double norm = kVisA / (tanh_at(kLambdaMax) - tanh_at(kLambdaMin));
  const double c = std::cosh(kVisA * (lambda - kVisCenter));
  return static_cast<float>(norm / (c * c));
}

float sample_visible_wavelength(float u) {
  static const double lo = tanh_at(kLambdaMin), hi = tanh_at(kLambdaMax);
  const double t = lo + static_cast<double>(u) * (hi - lo);
  const double lambda = kVisCenter + std::atanh(t) / kVisA;
  return std::clamp(static_cast<float>(lambda), kLambdaMin, kLambdaMax);
}

SampledWavelengths SampledWavelengths::sample_uniform(float u, float lambda_min, float lambda_max) {
  SampledWavelengths w;
  const float range = lambda_max - lambda_min;
  w.lambda_[0] = lambda_min + wrap01(u) * range;
  const float delta = range / kSpectrumSamples;
  for (int i = 1; i < kSpectrumSamples; ++i) {
    float l = w.lambda_[i - 1] + delta;
    if (l > lambda_max) l = lambda_min + (l - lambda_max);
    w.lambda_[i] = l;
  }
  w.pdf_.fill(range > 0.0f ? 1.0f / range : 0.0f);
  return w;
}

SampledWavelengths SampledWavelengths::sample_visible(float u) {
  SampledWavelengths w;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float up = wrap01(u + static_cast<float>(i) / kSpectrumSamples);
    w.lambda_[i] = sample_visible_wavelength(up);
    w.pdf_[i] = visible_wavelength_pdf(w.lambda_[i]);
  }
  return w;
}

void SampledWavelengths::terminate_secondary() {
  if (secondary_terminated()) return;
  for (int i = 1; i < kSpectrumSamples; ++i) pdf_[i] = 0.0f;
  pdf_[0] /= kSpectrumSamples;
}

bool SampledWavelengths::secondary_terminated() const {
  for (int i = 1; i < kSpectrumSamples; ++i)
    if (pdf_[i] != 0.0f) return false;
  return true;
}

}  // namespace photon::spectral

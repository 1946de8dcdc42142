#include "photon/spectral/sampled_spectrum.h"

#include <algorithm>

namespace photon::spectral {
namespace {

// visible_wavelength_pdf(lambda) = k / cosh^2(a (lambda - c)) = k (1 - tanh^2(a (lambda - c)));
// its CDF is (tanh(a (lambda - c)) - T0) / (T1 - T0) with T0, T1 the tanh at 360 and 830 nm.
constexpr float kVisA = 0.0072f;
constexpr float kVisCenter = 538.0f;

struct VisibleConstants {
  float t0, t1, k;
};
const VisibleConstants& visible_constants() {
  static const VisibleConstants c = [] {
    const double t0 = std::tanh(0.0072 * (360.0 - 538.0));
    const double t1 = std::tanh(0.0072 * (830.0 - 538.0));
    return VisibleConstants{static_cast<float>(t0), static_cast<float>(t1),
                            static_cast<float>(0.0072 / (t1 - t0))};
  }();
  return c;
}

float wrap01(float u) {
  return u - std::floor(u);
}

// The wavelength for u and its pdf, from one tanh value t: lambda = c + atanh(t) / a and
// pdf = k (1 - t^2), no cosh needed.
float sample_visible_with_pdf(float u, float* pdf) {
  const VisibleConstants& c = visible_constants();
  const float t = std::clamp(c.t0 + u * (c.t1 - c.t0), c.t0, c.t1);
  *pdf = c.k * (1.0f - t * t);
  const float lambda = kVisCenter + 0.5f * std::log((1.0f + t) / (1.0f - t)) / kVisA;
  return std::clamp(lambda, kLambdaMin, kLambdaMax);
}

}  // namespace

float visible_wavelength_pdf(float lambda) {
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0.0f;
  const float t = std::tanh(kVisA * (lambda - kVisCenter));
  return visible_constants().k * (1.0f - t * t);
}

float sample_visible_wavelength(float u) {
  float pdf;
  return sample_visible_with_pdf(u, &pdf);
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
    w.lambda_[i] = sample_visible_with_pdf(up, &w.pdf_[i]);
  }
  return w;
}

SampledWavelengths SampledWavelengths::sample_visible(float u, int n) {
  n = std::clamp(n, 1, kSpectrumSamples);
  if (n == kSpectrumSamples) return sample_visible(u);
  SampledWavelengths w;
  const float scale = static_cast<float>(n) / kSpectrumSamples;
  for (int i = 0; i < n; ++i) {
    const float up = wrap01(u + static_cast<float>(i) / n);
    w.lambda_[i] = sample_visible_with_pdf(up, &w.pdf_[i]);
    w.pdf_[i] *= scale;
  }
  // Unused wavelengths keep a valid value (the hero's) and pdf 0.
  for (int i = n; i < kSpectrumSamples; ++i) w.lambda_[i] = w.lambda_[0];
  return w;
}

SampledWavelengths SampledWavelengths::single(float lambda, float pdf) {
  SampledWavelengths w;
  w.lambda_.fill(lambda);
  w.pdf_[0] = pdf / kSpectrumSamples;
  return w;
}

void SampledWavelengths::terminate_secondary() {
  if (secondary_terminated()) return;
  const int n = active_count();
  for (int i = 1; i < kSpectrumSamples; ++i) pdf_[i] = 0.0f;
  pdf_[0] /= static_cast<float>(n);
}

int SampledWavelengths::active_count() const {
  int n = 0;
  for (float p : pdf_) n += p > 0.0f ? 1 : 0;
  return n;
}

bool SampledWavelengths::secondary_terminated() const {
  for (int i = 1; i < kSpectrumSamples; ++i)
    if (pdf_[i] != 0.0f) return false;
  return true;
}

}  // namespace photon::spectral

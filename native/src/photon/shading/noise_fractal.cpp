#include "photon/shading/noise_fractal.h"

#include <algorithm>
#include <cmath>

namespace photon::noise {
namespace {

// Cycles' mix(a, b, t) = a + t (b - a).
inline float mix(float a, float b, float t) {
  return a + t * (b - a);
}

template <int N>
float fbm(Point<N> p, float detail, float roughness, float lacunarity, bool normalize) {
  float fscale = 1.0f, amp = 1.0f, maxamp = 0.0f, sum = 0.0f;
  const int whole = static_cast<int>(detail);
  for (int i = 0; i <= whole; ++i) {
    const float t = snoise_wrapped<N>(p * fscale);
    sum += t * amp;
    maxamp += amp;
    amp *= roughness;
    fscale *= lacunarity;
  }
  const float rmd = detail - std::floor(detail);
  if (rmd != 0.0f) {
    const float t = snoise_wrapped<N>(p * fscale);
    const float sum2 = sum + t * amp;
    return normalize ? mix(0.5f * sum / maxamp + 0.5f, 0.5f * sum2 / (maxamp + amp) + 0.5f, rmd)
                     : mix(sum, sum2, rmd);
  }
  return normalize ? 0.5f * sum / maxamp + 0.5f : sum;
}

template <int N>
float multi_fractal(Point<N> p, float detail, float roughness, float lacunarity) {
  float value = 1.0f, pwr = 1.0f;
  const int whole = static_cast<int>(detail);
  for (int i = 0; i <= whole; ++i) {
    value *= (pwr * snoise_wrapped<N>(p) + 1.0f);
    pwr *= roughness;
    p = p * lacunarity;
  }
  const float rmd = detail - std::floor(detail);
  if (rmd != 0.0f) value *= (rmd * pwr * snoise_wrapped<N>(p) + 1.0f);
  return value;
}

template <int N>
float hetero_terrain(Point<N> p, float detail, float roughness, float lacunarity, float offset) {
  float pwr = roughness;
  // The first octave is unscaled; later ones are scaled by the value so far.
  float value = offset + snoise_wrapped<N>(p);
  p = p * lacunarity;
  const int whole = static_cast<int>(detail);
  for (int i = 1; i <= whole; ++i) {
    const float increment = (snoise_wrapped<N>(p) + offset) * pwr * value;
    value += increment;
    pwr *= roughness;
    p = p * lacunarity;
  }
  const float rmd = detail - std::floor(detail);
  if (rmd != 0.0f) {
    const float increment = (snoise_wrapped<N>(p) + offset) * pwr * value;
    value += rmd * increment;
  }
  return value;
}

template <int N>
float hybrid_multi_fractal(Point<N> p, float detail, float roughness, float lacunarity,
                           float offset, float gain) {
  float pwr = 1.0f, value = 0.0f, weight = 1.0f;
  const int whole = static_cast<int>(detail);
  for (int i = 0; (weight > 0.001f) && (i <= whole); ++i) {
    if (weight > 1.0f) weight = 1.0f;
    const float signal = (snoise_wrapped<N>(p) + offset) * pwr;
    pwr *= roughness;
    value += weight * signal;
    weight *= gain * signal;
    p = p * lacunarity;
  }
  const float rmd = detail - std::floor(detail);
  if ((rmd != 0.0f) && (weight > 0.001f)) {
    if (weight > 1.0f) weight = 1.0f;
    const float signal = (snoise_wrapped<N>(p) + offset) * pwr;
    value += rmd * weight * signal;
  }
  return value;
}

template <int N>
float ridged_multi_fractal(Point<N> p, float detail, float roughness, float lacunarity,
                           float offset, float gain) {
  float pwr = roughness;
  float signal = offset - std::fabs(snoise_wrapped<N>(p));
  signal *= signal;
  float value = signal;
  float weight = 1.0f;
  const int whole = static_cast<int>(detail);
  for (int i = 1; i <= whole; ++i) {
    p = p * lacunarity;
    weight = std::clamp(signal * gain, 0.0f, 1.0f);
    if (!(weight >= 0.0f)) weight = 0.0f;  // Cycles' saturatef of NaN
    signal = offset - std::fabs(snoise_wrapped<N>(p));
    signal *= signal;
    signal *= weight;
    value += signal * pwr;
    pwr *= roughness;
  }
  return value;
}

}  // namespace

template <int N>
float snoise_wrapped(const Point<N>& p) {
  Point<N> q;
  for (int i = 0; i < N; ++i) {
    const float correction = 0.5f * static_cast<float>(std::fabs(p[i]) >= 1000000.0f);
    q[i] = std::fmod(p[i], 100000.0f) + correction;
  }
  return snoise<N>(q);
}

template <int N>
float fractal(const Point<N>& p, const FractalParams& f) {
  switch (f.type) {
    case FractalType::kMultifractal:
      return multi_fractal<N>(p, f.detail, f.roughness, f.lacunarity);
    case FractalType::kFbm:
      return fbm<N>(p, f.detail, f.roughness, f.lacunarity, f.normalize);
    case FractalType::kHybrid:
      return hybrid_multi_fractal<N>(p, f.detail, f.roughness, f.lacunarity, f.offset, f.gain);
    case FractalType::kRidged:
      return ridged_multi_fractal<N>(p, f.detail, f.roughness, f.lacunarity, f.offset, f.gain);
    case FractalType::kHeteroTerrain:
      return hetero_terrain<N>(p, f.detail, f.roughness, f.lacunarity, f.offset);
  }
  return 0.0f;
}

template <int N>
float noise_texture_4x(Point<N> p, const FractalParams& params, float distortion, Vec3* color) {
  if (distortion != 0.0f) {
    Point<N> offset;
    for (int i = 0; i < N; ++i)
      offset[i] = snoise_wrapped<N>(p + random_offset<N>(static_cast<float>(i))) * distortion;
    p = p + offset;
  }
  const float value = fractal<N>(p, params);
  if (color != nullptr) {
    *color = Vec3(value, fractal<N>(p + random_offset<N>(float(N)), params),
                  fractal<N>(p + random_offset<N>(float(N + 1)), params));
  }
  return value;
}

float fbm_3d_4x(const Vec3& p, float detail, float roughness, float lacunarity, bool normalize) {
  return fbm<3>(point(p), detail, roughness, lacunarity, normalize);
}

template float snoise_wrapped<1>(const Point<1>&);
template float snoise_wrapped<2>(const Point<2>&);
template float snoise_wrapped<3>(const Point<3>&);
template float snoise_wrapped<4>(const Point<4>&);
template float fractal<1>(const Point<1>&, const FractalParams&);
template float fractal<2>(const Point<2>&, const FractalParams&);
template float fractal<3>(const Point<3>&, const FractalParams&);
template float fractal<4>(const Point<4>&, const FractalParams&);
template float noise_texture_4x<1>(Point<1>, const FractalParams&, float, Vec3*);
template float noise_texture_4x<2>(Point<2>, const FractalParams&, float, Vec3*);
template float noise_texture_4x<3>(Point<3>, const FractalParams&, float, Vec3*);
template float noise_texture_4x<4>(Point<4>, const FractalParams&, float, Vec3*);

}  // namespace photon::noise

#include "photon/shading/noise.h"

#include <climits>
#include <cmath>

#include "photon/shading/hash.h"

namespace photon::noise {
namespace {

// Lattice cell and position inside it. Out-of-range cells take INT_MIN, the value x86's truncating
// conversion gives Cycles there (a C++ cast would be undefined behaviour).
inline float floor_frac(float x, int32_t* cell) {
  float f = std::floor(x);
  *cell = (std::fabs(f) < 2147483648.0f) ? static_cast<int32_t>(f) : INT_MIN;
  return x - static_cast<float>(*cell);
}

// Perlin 2002, eq. for the quintic interpolant: 6t^5 - 15t^4 + 10t^3.
inline float fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}
inline float negate_if(float v, uint32_t condition) {
  return condition ? -v : v;
}
inline float mix(float a, float b, float t) {
  return a + t * (b - a);
}
inline uint32_t u(int32_t i) {
  return static_cast<uint32_t>(i);
}

// Gradients from the hash's low bits (Perlin 2002 picks among cube-edge directions; Blender uses
// 16 magnitudes in 1D, 8 directions in 2D, 12+4 cube edges in 3D and 32 edges of the 4D cube).
inline float grad1(uint32_t hash, float x) {
  uint32_t h = hash & 15u;
  float g = static_cast<float>(1u + (h & 7u));
  return negate_if(g, h & 8u) * x;
}
inline float grad2(uint32_t hash, float x, float y) {
  uint32_t h = hash & 7u;
  float a = h < 4u ? x : y;
  float b = 2.0f * (h < 4u ? y : x);
  return negate_if(a, h & 1u) + negate_if(b, h & 2u);
}
inline float grad3(uint32_t hash, float x, float y, float z) {
  uint32_t h = hash & 15u;
  float a = h < 8u ? x : y;
  float b = h < 4u ? y : ((h == 12u || h == 14u) ? x : z);
  return negate_if(a, h & 1u) + negate_if(b, h & 2u);
}
inline float grad4(uint32_t hash, float x, float y, float z, float w) {
  uint32_t h = hash & 31u;
  float a = h < 24u ? x : y;
  float b = h < 16u ? y : z;
  float c = h < 8u ? z : w;
  return negate_if(a, h & 1u) + negate_if(b, h & 2u) + negate_if(c, h & 4u);
}

inline float bilinear(float v0, float v1, float v2, float v3, float x, float y) {
  float x1 = 1.0f - x;
  return (1.0f - y) * (v0 * x1 + v1 * x) + y * (v2 * x1 + v3 * x);
}
inline float trilinear(const float v[8], float x, float y, float z) {
  float x1 = 1.0f - x, y1 = 1.0f - y, z1 = 1.0f - z;
  return z1 * (y1 * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x)) +
         z * (y1 * (v[4] * x1 + v[5] * x) + y * (v[6] * x1 + v[7] * x));
}

// Per-dimension factors that bring each noise to about [-1, 1] (Blender's noise_scale{1..4}d).
template <int N>
constexpr float kScale = 0.0f;
template <>
constexpr float kScale<1> = 0.2500f;
template <>
constexpr float kScale<2> = 0.6616f;
template <>
constexpr float kScale<3> = 0.9820f;
template <>
constexpr float kScale<4> = 0.8344f;

template <int N>
float perlin(const Point<N>& p);
template <>
float perlin<1>(const Point<1>& p) {
  return perlin_1d(p[0]);
}
template <>
float perlin<2>(const Point<2>& p) {
  return perlin_2d(p);
}
template <>
float perlin<3>(const Point<3>& p) {
  return perlin_3d(p);
}
template <>
float perlin<4>(const Point<4>& p) {
  return perlin_4d(p);
}

}  // namespace

float perlin_1d(float x) {
  int32_t X;
  float fx = floor_frac(x, &X);
  float t = fade(fx);
  return mix(grad1(hash::hash_uint(u(X)), fx), grad1(hash::hash_uint(u(X) + 1u), fx - 1.0f), t);
}

float perlin_2d(const Point<2>& p) {
  int32_t X, Y;
  float fx = floor_frac(p[0], &X);
  float fy = floor_frac(p[1], &Y);
  uint32_t x0 = u(X), x1 = u(X) + 1u, y0 = u(Y), y1 = u(Y) + 1u;
  return bilinear(grad2(hash::hash_uint2(x0, y0), fx, fy),
                  grad2(hash::hash_uint2(x1, y0), fx - 1.0f, fy),
                  grad2(hash::hash_uint2(x0, y1), fx, fy - 1.0f),
                  grad2(hash::hash_uint2(x1, y1), fx - 1.0f, fy - 1.0f), fade(fx), fade(fy));
}

float perlin_3d(const Point<3>& p) {
  int32_t X, Y, Z;
  float fx = floor_frac(p[0], &X);
  float fy = floor_frac(p[1], &Y);
  float fz = floor_frac(p[2], &Z);
  float v[8];
  // Corner i sits at (X + bit0, Y + bit1, Z + bit2).
  for (uint32_t i = 0; i < 8; ++i) {
    uint32_t dx = i & 1u, dy = (i >> 1) & 1u, dz = (i >> 2) & 1u;
    v[i] = grad3(hash::hash_uint3(u(X) + dx, u(Y) + dy, u(Z) + dz), fx - static_cast<float>(dx),
                 fy - static_cast<float>(dy), fz - static_cast<float>(dz));
  }
  return trilinear(v, fade(fx), fade(fy), fade(fz));
}

float perlin_4d(const Point<4>& p) {
  int32_t X, Y, Z, W;
  float fx = floor_frac(p[0], &X);
  float fy = floor_frac(p[1], &Y);
  float fz = floor_frac(p[2], &Z);
  float fw = floor_frac(p[3], &W);
  float v[16];
  for (uint32_t i = 0; i < 16; ++i) {
    uint32_t dx = i & 1u, dy = (i >> 1) & 1u, dz = (i >> 2) & 1u, dw = (i >> 3) & 1u;
    v[i] = grad4(hash::hash_uint4(u(X) + dx, u(Y) + dy, u(Z) + dz, u(W) + dw),
                 fx - static_cast<float>(dx), fy - static_cast<float>(dy),
                 fz - static_cast<float>(dz), fw - static_cast<float>(dw));
  }
  float x = fade(fx), y = fade(fy), z = fade(fz);
  return mix(trilinear(v, x, y, z), trilinear(v + 8, x, y, z), fade(fw));
}

template <int N>
float snoise(const Point<N>& p) {
  float r = perlin<N>(p);
  return std::isfinite(r) ? kScale<N> * r : 0.0f;
}

template <int N>
float fractal_noise(const Point<N>& p, float octaves, float roughness) {
  octaves = std::clamp(octaves, 0.0f, 15.0f);  // NaN stays NaN: treat it as 0
  if (!(octaves >= 0.0f)) octaves = 0.0f;
  roughness = std::clamp(roughness, 0.0f, 1.0f);
  if (!(roughness >= 0.0f)) roughness = 0.0f;
  float scale = 1.0f, amp = 1.0f, max_amp = 0.0f, sum = 0.0f;
  int whole = static_cast<int>(octaves);
  for (int i = 0; i <= whole; ++i) {
    sum += noise<N>(p * scale) * amp;
    max_amp += amp;
    amp *= roughness;
    scale *= 2.0f;
  }
  float rmd = octaves - std::floor(octaves);
  if (rmd == 0.0f) return sum / max_amp;
  float sum2 = sum + noise<N>(p * scale) * amp;
  return (1.0f - rmd) * (sum / max_amp) + rmd * (sum2 / (max_amp + amp));
}

template <int N>
Point<N> random_offset(float seed) {
  Point<N> o;
  if (N == 1) {
    o[0] = 100.0f + hash::hash_float_to_float(seed) * 100.0f;
  } else {
    for (int i = 0; i < N; ++i)
      o[i] = 100.0f + hash::hash_float2_to_float(seed, static_cast<float>(i)) * 100.0f;
  }
  return o;
}

template float snoise<1>(const Point<1>&);
template float snoise<2>(const Point<2>&);
template float snoise<3>(const Point<3>&);
template float snoise<4>(const Point<4>&);
template float fractal_noise<1>(const Point<1>&, float, float);
template float fractal_noise<2>(const Point<2>&, float, float);
template float fractal_noise<3>(const Point<3>&, float, float);
template float fractal_noise<4>(const Point<4>&, float, float);
template Point<1> random_offset<1>(float);
template Point<2> random_offset<2>(float);
template Point<3> random_offset<3>(float);
template Point<4> random_offset<4>(float);

}  // namespace photon::noise

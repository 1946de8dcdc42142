// Gradient noise as Blender's procedural textures compute it: Perlin's improved noise ("Improving
// Noise", SIGGRAPH 2002: quintic fade 6t^5 - 15t^4 + 10t^3, gradients picked from the low bits of a
// lattice hash) in 1-4 dimensions, with the lattice hashed by lookup3 (shading/hash.h) instead of a
// permutation table, and the per-dimension scale factors Cycles applies so each dimension spans
// about [-1, 1]. On top: fBm (Musgrave, "Texturing and Modeling", ch. 16) with Blender's fractional
// last octave. Pure functions, usable by any node family.
#pragma once

#include "photon/base/math.h"

namespace photon::noise {

// A point of N dimensions (4D is Vector then W).
template <int N>
struct Point {
  float v[N];
  float operator[](int i) const { return v[i]; }
  float& operator[](int i) { return v[i]; }
};

inline Point<2> point(const Vec2& v) {
  return {v.x, v.y};
}
inline Point<3> point(const Vec3& v) {
  return {v.x, v.y, v.z};
}
inline Point<4> point(const Vec3& v, float w) {
  return {v.x, v.y, v.z, w};
}

template <int N>
inline Point<N> operator*(Point<N> p, float s) {
  for (float& c : p.v) c *= s;
  return p;
}
template <int N>
inline Point<N> operator+(Point<N> a, const Point<N>& b) {
  for (int i = 0; i < N; ++i) a[i] += b[i];
  return a;
}

// Raw Perlin noise (about [-1, 1] before the per-dimension scale).
float perlin_1d(float x);
float perlin_2d(const Point<2>& p);
float perlin_3d(const Point<3>& p);
float perlin_4d(const Point<4>& p);

// Signed noise, scaled to about [-1, 1]; 0 where the raw value is not finite.
template <int N>
float snoise(const Point<N>& p);
// Unsigned noise: 0.5 + 0.5 snoise.
template <int N>
float noise(const Point<N>& p) {
  return 0.5f * snoise<N>(p) + 0.5f;
}

// fBm of unsigned noise, octaves clamped to [0, 15]: octave i has frequency 2^i and amplitude
// roughness^i; a fractional octave count blends the normalised sums with and without the next
// octave. Result normalised by the summed amplitudes (about [0, 1]).
template <int N>
float fractal_noise(const Point<N>& p, float octaves, float roughness);

inline float snoise_1d(float x) {
  return snoise<1>(Point<1>{x});
}
inline float fractal_noise_1d(float x, float octaves, float roughness) {
  return fractal_noise<1>(Point<1>{x}, octaves, roughness);
}
inline float fractal_noise_3d(const Vec3& p, float octaves, float roughness) {
  return fractal_noise<3>(point(p), octaves, roughness);
}

// The offsets Blender adds to decorrelate the noises of one node (distortion per axis, extra
// colour channels): 100 + 100 * hash(seed, axis) per component.
template <int N>
Point<N> random_offset(float seed);

}  // namespace photon::noise

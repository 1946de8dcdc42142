// The integer and float hashes behind Blender's procedural textures (Noise, Voronoi, White Noise,
// Musgrave): Bob Jenkins' lookup3 final mix ("lookup3.c", 2006) seeded as Cycles seeds it, so the
// same coordinates give the same random numbers in Photon and in Cycles.
#pragma once

#include <cstdint>
#include <cstring>

#include "photon/base/math.h"

namespace photon::hash {

inline uint32_t rotl(uint32_t x, int k) {
  return (x << k) | (x >> (32 - k));
}

// lookup3's mix() and final() on (a, b, c).
inline void mix(uint32_t& a, uint32_t& b, uint32_t& c) {
  a -= c, a ^= rotl(c, 4), c += b;
  b -= a, b ^= rotl(a, 6), a += c;
  c -= b, c ^= rotl(b, 8), b += a;
  a -= c, a ^= rotl(c, 16), c += b;
  b -= a, b ^= rotl(a, 19), a += c;
  c -= b, c ^= rotl(b, 4), b += a;
}
inline void final_mix(uint32_t& a, uint32_t& b, uint32_t& c) {
  c ^= b, c -= rotl(b, 14);
  a ^= c, a -= rotl(c, 11);
  b ^= a, b -= rotl(a, 25);
  c ^= b, c -= rotl(b, 16);
  a ^= c, a -= rotl(c, 4);
  b ^= a, b -= rotl(a, 14);
  c ^= b, c -= rotl(b, 24);
}

// lookup3's hashword() of 1-4 words with initval 13.
inline uint32_t hash_uint(uint32_t kx) {
  uint32_t a, b, c;
  a = b = c = 0xdeadbeefu + (1u << 2) + 13u;
  a += kx;
  final_mix(a, b, c);
  return c;
}
inline uint32_t hash_uint2(uint32_t kx, uint32_t ky) {
  uint32_t a, b, c;
  a = b = c = 0xdeadbeefu + (2u << 2) + 13u;
  b += ky;
  a += kx;
  final_mix(a, b, c);
  return c;
}
inline uint32_t hash_uint3(uint32_t kx, uint32_t ky, uint32_t kz) {
  uint32_t a, b, c;
  a = b = c = 0xdeadbeefu + (3u << 2) + 13u;
  c += kz;
  b += ky;
  a += kx;
  final_mix(a, b, c);
  return c;
}
inline uint32_t hash_uint4(uint32_t kx, uint32_t ky, uint32_t kz, uint32_t kw) {
  uint32_t a, b, c;
  a = b = c = 0xdeadbeefu + (4u << 2) + 13u;
  a += kx;
  b += ky;
  c += kz;
  mix(a, b, c);
  a += kw;
  final_mix(a, b, c);
  return c;
}

inline uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Hashes to [0, 1].
inline float uint_to_float(uint32_t h) {
  return static_cast<float>(h) / static_cast<float>(0xFFFFFFFFu);
}
inline float hash_uint_to_float(uint32_t kx) {
  return uint_to_float(hash_uint(kx));
}
inline float hash_uint2_to_float(uint32_t kx, uint32_t ky) {
  return uint_to_float(hash_uint2(kx, ky));
}
inline float hash_uint3_to_float(uint32_t kx, uint32_t ky, uint32_t kz) {
  return uint_to_float(hash_uint3(kx, ky, kz));
}
inline float hash_uint4_to_float(uint32_t kx, uint32_t ky, uint32_t kz, uint32_t kw) {
  return uint_to_float(hash_uint4(kx, ky, kz, kw));
}

inline float hash_float_to_float(float k) {
  return hash_uint_to_float(float_bits(k));
}
inline float hash_float2_to_float(float x, float y) {
  return hash_uint2_to_float(float_bits(x), float_bits(y));
}
inline float hash_float3_to_float(const Vec3& k) {
  return hash_uint3_to_float(float_bits(k.x), float_bits(k.y), float_bits(k.z));
}
inline float hash_float4_to_float(const Vec3& k, float w) {
  return hash_uint4_to_float(float_bits(k.x), float_bits(k.y), float_bits(k.z), float_bits(w));
}

}  // namespace photon::hash

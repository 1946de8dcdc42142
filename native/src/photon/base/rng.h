// Counter-based random numbers: every value is a pure function of (seed, pixel, sample, dimension),
// so images do not depend on thread count, tile size or tile order.
#pragma once

#include <cstdint>

#include "photon/base/math.h"

namespace photon {

// SplitMix64 finaliser (Steele et al. 2014): a strong 64-bit bijective mixer.
inline uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

inline uint64_t hash_combine(uint64_t a, uint64_t b) {
  return mix64(a ^ mix64(b));
}

// Maps the top 24 bits to [0, 1) exactly representable in float.
inline float to_unit_float(uint64_t bits) {
  return static_cast<float>(bits >> 40) * (1.0f / 16777216.0f);
}

// A pseudo-random permutation of [0, count) chosen by `key`: hash-based bijection on the next
// power of two with cycle walking (after Kensler 2013, "Correlated Multi-Jittered Sampling",
// permute()). Every index maps to a distinct index, so a stratified point set stays stratified.
inline uint32_t permute_index(uint32_t i, uint32_t count, uint32_t key) {
  if (count <= 1) return 0;
  uint32_t mask = count - 1;
  mask |= mask >> 1;
  mask |= mask >> 2;
  mask |= mask >> 4;
  mask |= mask >> 8;
  mask |= mask >> 16;
  do {
    // Each step is invertible on (mask + 1)-bit integers: xor with a constant, odd
    // multiplication and xor with a right shift of the masked value.
    i ^= key;
    i *= 0xE170893Du;
    i ^= key >> 16;
    i ^= (i & mask) >> 4;
    i ^= key >> 8;
    i *= 0x0929EB3Fu;
    i ^= key >> 23;
    i ^= (i & mask) >> 1;
    i *= 1u | key >> 27;
    i *= 0x6935FA69u;
    i ^= (i & mask) >> 11;
    i *= 0x74DCB303u;
    i ^= (i & mask) >> 2;
    i *= 0x9E501CC3u;
    i ^= (i & mask) >> 2;
    i *= 0xC860A3DFu;
    i &= mask;
    i ^= i >> 5;
  } while (i >= count);
  return (i + key) % count;
}

// A per-(pixel, sample) stream. Dimensions are consumed in order; the same call sequence
// always yields the same numbers.
//
// 2D requests use the R2 low-discrepancy sequence (Roberts 2018): the first `sample_count`
// points are well stratified in the unit square. Each 2D dimension visits those points in its
// own pseudo-random order (permute_index) and with its own per-pixel Cranley-Patterson rotation,
// so pixel jitter, lens and light samples are each stratified over a pixel's samples yet
// independent of one another and of neighbouring pixels.
class Sampler {
 public:
  // `sample_count` is the number of samples the pixel will take (0 = unknown: indices are then
  // scrambled over the whole 32-bit range, which keeps independence but not stratification).
  // With `block_first`, the samples [block_first, block_first + sample_count) are stratified
  // among themselves: a pixel whose sample count is not known ahead (a time limit) takes its
  // samples in blocks, and as the blocks are consecutive runs of the R2 sequence their union is
  // as well stratified as one block of them all.
  Sampler(uint64_t seed, uint64_t stream, uint32_t sample_index, uint32_t sample_count = 0,
          uint32_t block_first = 0)
      : key_(hash_combine(seed, stream)),
        sample_(sample_index),
        count_(sample_count),
        block_first_(block_first) {}

  float get_1d() { return to_unit_float(mix64(key_ ^ mix64(sample_ * 0x100000001B3ull + dim_++))); }

  // A number in [0, 1) outside the dimension sequence (every get_1d / get_2d stays as it was),
  // told apart from other such numbers by `tag`: the sample indices of a pixel (of
  // `sample_count`) are stratified over [0, 1) in a per-pixel random order and jittered within
  // their stratum. Spectral rendering draws its wavelengths from it, so a spectral and an RGB
  // render of one seed share every other random number.
  float stratified_1d(uint64_t tag) const {
    const uint64_t h = mix64(key_ ^ mix64(tag ^ 0x5EC7A1ull));
    const float jitter = to_unit_float(mix64(h ^ sample_));
    if (!count_) return jitter;
    const uint32_t stratum = permute_index(static_cast<uint32_t>(sample_) - block_first_, count_,
                                           static_cast<uint32_t>(h >> 32));
    return clamp_below_one((static_cast<float>(stratum) + jitter) / static_cast<float>(count_));
  }

  Vec2 get_2d() {
    constexpr double kG = 1.32471795724474602596;  // plastic number
    constexpr double kA1 = 1.0 / kG, kA2 = 1.0 / (kG * kG);
    const uint64_t rot = mix64(key_ ^ (0xA5A5A5A5ull + dim_++));
    const uint32_t perm_key = static_cast<uint32_t>(rot >> 32);
    const uint32_t sample =
        count_ ? block_first_ +
                     permute_index(static_cast<uint32_t>(sample_) - block_first_, count_, perm_key)
               : static_cast<uint32_t>(mix64(sample_ ^ rot));
    double u = 0.5 + kA1 * sample + to_unit_float(rot);
    double v = 0.5 + kA2 * sample + to_unit_float(rot << 24);
    u -= static_cast<double>(static_cast<uint64_t>(u));
    v -= static_cast<double>(static_cast<uint64_t>(v));
    return {clamp_below_one(static_cast<float>(u)), clamp_below_one(static_cast<float>(v))};
  }

 private:
  static float clamp_below_one(float x) { return x < 1.0f ? x : 0.99999994f; }
  uint64_t key_;
  uint64_t sample_;
  uint32_t count_;
  uint32_t block_first_;
  uint64_t dim_ = 0;
};

}  // namespace photon

// Counter-based random numbers: every value is a pure function of (seed, pixel, sample, dimension),
// so images do not depend on thread count, tile size or tile order.
#pragma once

#include <cstdint>

#include "photon/math.h"

namespace photon {

// SplitMix64 finaliser (Steele et al. 2014): a strong 64-bit bijective mixer.
inline uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

inline uint64_t hash_combine(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b)); }

// Maps the top 24 bits to [0, 1) exactly representable in float.
inline float to_unit_float(uint64_t bits) {
  return static_cast<float>(bits >> 40) * (1.0f / 16777216.0f);
}

// A per-(pixel, sample) stream. Dimensions are consumed in order; the same call sequence
// always yields the same numbers.
//
// 2D requests use the R2 low-discrepancy sequence (Roberts 2018) indexed by the sample number and
// rotated per pixel and dimension (Cranley-Patterson rotation), which stratifies pixel jitter and
// light samples across a pixel's samples while decorrelating neighbouring pixels.
class Sampler {
 public:
  Sampler(uint64_t seed, uint64_t stream, uint32_t sample_index)
      : key_(hash_combine(seed, stream)), sample_(sample_index) {}

  float get_1d() { return to_unit_float(mix64(key_ ^ mix64(sample_ * 0x100000001B3ull + dim_++))); }

  Vec2 get_2d() {
    constexpr double kG = 1.32471795724474602596;  // plastic number
    constexpr double kA1 = 1.0 / kG, kA2 = 1.0 / (kG * kG);
    uint64_t rot = mix64(key_ ^ (0xA5A5A5A5ull + dim_++));
    double u = 0.5 + kA1 * sample_ + to_unit_float(rot);
    double v = 0.5 + kA2 * sample_ + to_unit_float(rot << 24);
    u -= static_cast<double>(static_cast<uint64_t>(u));
    v -= static_cast<double>(static_cast<uint64_t>(v));
    return {clamp_below_one(static_cast<float>(u)), clamp_below_one(static_cast<float>(v))};
  }

 private:
  static float clamp_below_one(float x) { return x < 1.0f ? x : 0.99999994f; }
  uint64_t key_;
  uint64_t sample_;
  uint64_t dim_ = 0;
};

}  // namespace photon

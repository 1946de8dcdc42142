// The Gabor Texture of Blender 4.3 (Cycles' kernel/svm/gabor.h): sparse convolution noise
// (Lagae et al., "Procedural Noise using Sparse Gabor Convolution", 2009) with Tavernier et al.'s
// phasor formulation ("Making Gabor Noise Fast and Normalized", 2019): 8 impulses per unit cell,
// each a Hann-windowed Gaussian times a complex sinusoid of the node's Frequency along an
// orientation randomised by (1 - Anisotropy), summed over the 3^N neighbouring cells.
#pragma once

#include "photon/base/math.h"

namespace photon::gabor {

struct Result {
  float value = 0.5f;      // the phasor's imaginary part, normalised into about [0, 1]
  float phase = 0.5f;      // its angle, mapped to [0, 1]
  float intensity = 0.0f;  // its length, normalised
};

// `p` already multiplied by Scale; `frequency` and `anisotropy` as the node's sockets.
Result gabor_2d(const Vec3& p, float frequency, float anisotropy, float orientation);
Result gabor_3d(const Vec3& p, float frequency, float anisotropy, const Vec3& orientation);

}  // namespace photon::gabor

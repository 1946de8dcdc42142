// The fractal noises of Blender 4.x's Noise Texture (Cycles 4.1+, kernel/svm/fractal_noise.h),
// which took in the Musgrave Texture's types: fBM with Lacunarity and optional normalisation,
// multifractal, hybrid multifractal, ridged multifractal and heterogeneous terrain, each with
// Detail + 1 octaves (a fractional last one), Roughness as the per-octave gain and Lacunarity as
// the per-octave frequency factor. The noise is Cycles 4.x's signed Perlin noise, which wraps
// every coordinate at 100000 (and shifts those beyond 1000000 by half a cell) so large
// coordinates keep their precision. Blender 3.4's Noise and Musgrave stay in noise.h and
// noise_nodes.cpp, unchanged.
#pragma once

#include <cstdint>

#include "photon/shading/noise.h"

namespace photon::noise {

// Blender 4.x's Noise Texture "noise_type", in the order of Cycles' NodeNoiseType.
enum class FractalType : uint32_t { kMultifractal, kFbm, kHybrid, kRidged, kHeteroTerrain };

struct FractalParams {
  FractalType type = FractalType::kFbm;
  float detail = 2.0f;  // already clamped to [0, 15]
  float roughness = 0.5f;
  float lacunarity = 2.0f;
  float offset = 0.0f;
  float gain = 1.0f;
  bool normalize = true;  // fBM only: map into about [0, 1]
};

// Cycles 4.x's snoise_Nd: the coordinate wrapped as described above, then snoise<N>.
template <int N>
float snoise_wrapped(const Point<N>& p);

// One fractal value at p (coordinates already multiplied by the node's Scale).
template <int N>
float fractal(const Point<N>& p, const FractalParams& params);

// The node's Fac and, when `color` is not null, Color: Distortion displaces the point first
// (each axis by its own noise), the colour's second and third channels sample offset points.
template <int N>
float noise_texture_4x(Point<N> p, const FractalParams& params, float distortion, Vec3* color);

// Cycles 4.x's noise_fbm(p, detail, roughness, lacunarity, normalize) of a 3D point, unclamped
// (the Wave Texture's distortion).
float fbm_3d_4x(const Vec3& p, float detail, float roughness, float lacunarity, bool normalize);

}  // namespace photon::noise

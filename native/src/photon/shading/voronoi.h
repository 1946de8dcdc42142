// Worley cellular noise ("A Cellular Texture Basis Function", Worley 1996) as Blender 3.4's
// Voronoi Texture computes it in Cycles: one jittered feature point per unit cell, hashed from the
// cell's integer coordinates with lookup3 (shading/hash.h), searched in the 3^N neighbourhood (5^N
// for Smooth F1). Smooth F1 is Inigo Quilez's polynomial smooth minimum ("Smooth Voronoi", 2014)
// blending distance, colour and position; Distance to Edge is his exact border distance
// ("Voronoi edges", 2013) over the 3^N window. All functions are pure and take coordinates already
// multiplied by the node's Scale.
#pragma once

#include <cstdint>

#include "photon/base/math.h"

namespace photon::voronoi {

enum class Feature : uint32_t { kF1, kF2, kSmoothF1, kDistanceToEdge, kNSphereRadius };
enum class Metric : uint32_t { kEuclidean, kManhattan, kChebychev, kMinkowski };

struct Params {
  Feature feature = Feature::kF1;
  Metric metric = Metric::kEuclidean;  // 2D-4D only: 1D distances are always |a - b|
  float exponent = 0.5f;               // Minkowski
  float randomness = 1.0f;             // jitter of the feature points, in [0, 1]
  float smoothness = 0.5f;             // Smooth F1's blend width (the node's Smoothness / 2)
};

// What a feature produces, in scaled coordinates; fields a feature does not produce stay zero.
struct Result {
  float distance = 0.0f;
  Vec3 color{0.0f};
  float position[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // x, y, z, w of the feature point (1D: w only)
  float radius = 0.0f;                           // N-Sphere Radius
};

Result voronoi_1d(float w, const Params& params);
Result voronoi_2d(float x, float y, const Params& params);
Result voronoi_3d(const Vec3& p, const Params& params);
Result voronoi_4d(const Vec3& p, float w, const Params& params);

}  // namespace photon::voronoi

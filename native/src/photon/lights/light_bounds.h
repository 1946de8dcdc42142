// Bounds of a group of emitters for the light tree.
#pragma once

#include <cmath>

#include "photon/base/math.h"

namespace photon {

// What a light tree node needs to bound the light of the emitters below it (Conty Estevez &
// Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting", sec. 4.1): the
// box of their positions, the cone of their normals (axis, theta_o) and how far beyond a normal
// they emit (theta_e: pi/2 for cosine emitters and point lights, the half angle for a spot),
// and their total power.
struct LightBounds {
  Vec3 lo{INFINITY}, hi{-INFINITY};
  Vec3 axis{0.0f, 0.0f, 1.0f};
  float cos_theta_o = 1.0f;  // -1: normals in every direction (point lights, two-sided surfaces)
  float cos_theta_e = 0.0f;
  float power = 0.0f;     // scalar flux (mean of the channels), W
  bool infinite = false;  // at infinity (sun, world): not in the tree
  bool empty() const { return !(lo.x <= hi.x); }
};

// Union of two bounds: boxes joined, normal cones merged into the smallest cone holding both
// (Conty Estevez & Kulla 2018, Algorithm 1), powers added.
LightBounds merge(const LightBounds& a, const LightBounds& b);

}  // namespace photon

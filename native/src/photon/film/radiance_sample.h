// What a camera sample brings to the film: its light, split into the light passes, and how much
// of the pixel it covers.
#pragma once

#include "photon/base/math.h"
#include "photon/render/accel.h"

namespace photon {

// The light passes a sample is split into (Direct, Indirect, Caustics, Photon Map), RGB each.
constexpr int kPassCount = 4;
constexpr int kPassFloats = 3 * kPassCount;

// What one camera sample sees, split into light passes whose sum is the Combined image.
struct RadianceSample {
  Vec3 direct;         // emission, direct light, and lights / world seen through specular paths
  Vec3 indirect;       // light that bounced off at least one diffuse surface
  Vec3 caustic;        // light that reached a diffuse surface through specular paths only
  Vec3 photon_map;     // a view of the stored photons (not light; not part of Combined)
  float alpha = 0.0f;  // 1 when the camera ray hit something that is not background
  // Share of the sample taken out by holdouts (the path's throughput into them): the pixel's
  // alpha is reduced by it whether or not the film is transparent, as in Cycles.
  float holdout = 0.0f;
  Vec3 radiance() const { return direct + indirect + caustic; }
};

// The first intersection of a camera ray, traced beforehand together with its neighbours.
struct CameraHit {
  bool found = false;
  Hit hit;
};

}  // namespace photon

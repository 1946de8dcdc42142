// Aiming caustic photons at specular objects. Jensen's projection maps (1996) mark the cells
// of a light's sphere of directions that see a specular object and emit caustic photons only
// through them; here the cells are replaced by the cones that bound each specular object's
// bounding sphere (a continuous projection map), sampled as a mixture so the density of every
// direction is known exactly and the photon's power stays unbiased.
#pragma once

#include <vector>

#include "photon/accel.h"
#include "photon/lights.h"

namespace photon {

// Bounding spheres of the instances that carry mirror or glass triangles. More than
// `max_targets` are merged into one sphere around all of them.
std::vector<BoundingSphere> specular_targets(const Scene& scene, const Accel& accel,
                                             size_t max_targets = 64);

// Directions from `origin` towards a set of spheres: cone k is picked with probability
// proportional to its solid angle, then a direction uniformly inside it.
class ConeMixture {
 public:
  ConeMixture(const Vec3& origin, const std::vector<BoundingSphere>& targets);
  bool empty() const { return cones_.empty(); }
  // Sum of the cones' solid angles over 4 pi (overlaps counted twice), at most 1.
  float coverage() const;
  bool sample(float u_pick, Vec2 u, Vec3* direction, float* pdf) const;
  float pdf(const Vec3& direction) const;

 private:
  struct Cone {
    Vec3 axis;
    float cos_max;  // -1: the origin is inside the sphere, every direction
    float solid_angle;
  };
  std::vector<Cone> cones_;
  float total_solid_angle_ = 0.0f;
};

// Points of a plane perpendicular to a parallel beam (the sun) covering the targets' discs:
// disc k is picked with probability proportional to its area, then a uniform point in it.
class DiscMixture {
 public:
  DiscMixture(const Vec3& beam_direction, const std::vector<BoundingSphere>& targets,
              float extra_radius);
  bool empty() const { return discs_.empty(); }
  float total_area() const { return total_area_; }
  // A point on the plane through the origin perpendicular to the beam, and its area density.
  void sample(float u_pick, Vec2 u, Vec3* point, float* pdf) const;
  float pdf(const Vec3& point) const;

 private:
  struct Disc {
    Vec3 center;  // projected onto the plane through the origin
    float radius;
  };
  Frame frame_;
  std::vector<Disc> discs_;
  float total_area_ = 0.0f;
};

}  // namespace photon

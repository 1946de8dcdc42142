// Aiming caustic photons at specular objects. Jensen's projection maps (1996) mark the cells
// of a light's sphere of directions that see a specular object and emit caustic photons only
// through them; here the cells are replaced by the cones that bound each specular object's
// bounding sphere (a continuous projection map), intersected with the directions the light
// actually emits into, and sampled as a mixture so the density of every direction is known
// exactly and the photon's power stays unbiased.
#pragma once

#include <vector>

#include "photon/base/spherical_caps.h"
#include "photon/lights/lights.h"

namespace photon {

// Directions from `origin` towards a set of spheres, restricted to the directions `region` the
// light emits into (a spot's cone, an area light's hemisphere; the whole sphere by default):
// piece k = region ∩ cone k is picked with probability proportional to its solid angle, then a
// direction uniformly inside it. The spheres may be enlarged by `extra_radius` (a spot light's
// disc, whose photons leave from up to that far off its centre).
class ConeMixture {
 public:
  ConeMixture(const Vec3& origin, const std::vector<BoundingSphere>& targets,
              const Cap& region = Cap::whole_sphere(), float extra_radius = 0.0f);
  bool empty() const { return pieces_.empty(); }
  // The pieces' solid angle (overlaps counted twice) over the region's, at most 1.
  float coverage() const;
  bool sample(float u_pick, Vec2 u, Vec3* direction, float* pdf) const;
  float pdf(const Vec3& direction) const;

 private:
  struct Piece {
    Cap cone;  // towards the target; the piece is cone ∩ region
    double solid_angle;
  };
  float pdf_counting(const Vec3& direction, size_t known_inside) const;
  Cap region_;
  std::vector<Piece> pieces_;
  double total_solid_angle_ = 0.0;
};

// Caustic photons from a sphere light of uniform radiance (centre, radius): for target k only
// the points whose tangent plane leaves part of target k in front can light it, a cap of the
// sphere's normals. Target k is picked by the solid angle it subtends from the centre, a point
// uniformly in its cap of normals, then a direction uniformly in the hemisphere above the point
// that also heads into target k's cone. The density is over area (on the sphere) times solid
// angle, summed over every target that could have produced the pair.
class SphereLightAim {
 public:
  SphereLightAim(const Vec3& center, float radius, const std::vector<BoundingSphere>& targets);
  bool empty() const { return aims_.empty(); }
  bool sample(float u_pick, Vec2 u_point, Vec2 u_dir, Vec3* normal, Vec3* direction,
              float* pdf) const;
  float pdf(const Vec3& normal, const Vec3& direction) const;

 private:
  struct Aim {
    BoundingSphere target;
    Cap normals;
    double weight;
  };
  double term(const Aim& a, const Vec3& normal, const Vec3& direction, bool known_inside) const;
  Vec3 center_;
  float radius_;
  std::vector<Aim> aims_;
  double total_weight_ = 0.0;
};

// Points of a plane perpendicular to a parallel beam (the sun) covering the targets' discs:
// disc k is picked with probability proportional to its area, then a uniform point in it.
class DiscMixture {
 public:
  DiscMixture(const Vec3& beam_direction, const std::vector<BoundingSphere>& targets);
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

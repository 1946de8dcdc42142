// The world's portals (scene.h Portal) as sampling techniques, as Cycles defines them: from a
// point on a portal's inner side, a direction through one of the portals that face it, picked
// uniformly, sampled over the portal's solid angle (rectangles, spherical_rectangle.h) or
// area (ellipses); its density is the mean over the facing portals of each one's density of
// that direction (0 for the portals it misses). For photons, lines through a point of the
// portals (picked by area) in a cosine-weighted direction into the room.
#pragma once

#include <vector>

#include "photon/base/math.h"
#include "photon/scene/scene.h"

namespace photon {

class PortalSet {
 public:
  PortalSet() = default;
  // Portals without area or with non-finite geometry are left out (`skipped` counts them).
  explicit PortalSet(const std::vector<Portal>& portals, size_t* skipped = nullptr);

  bool empty() const { return portals_.empty(); }
  size_t size() const { return portals_.size(); }

  // How many portals have `p` on their inner side (where their light goes).
  size_t facing(const Vec3& p) const;
  // A direction from `p` through a portal facing it and the technique's solid-angle density of
  // it; false when no portal faces p.
  bool sample(const Vec3& p, float u_pick, Vec2 u, Vec3* wi, float* pdf) const;
  // The same density for any direction from p.
  float pdf(const Vec3& p, const Vec3& wi) const;

  // A line into the room: a point of a portal picked by area and a direction cosine-weighted
  // about its `direction`. Its density in projected area x solid angle is crossings() / (pi x
  // total area): each portal it crosses could have made it.
  void sample_line(float u_pick, Vec2 u_point, Vec2 u_dir, Vec3* point, Vec3* direction) const;
  // The portals a line through `point` along `direction` crosses the way their light goes.
  int crossings(const Vec3& point, const Vec3& direction) const;
  float total_area() const { return total_area_; }

 private:
  struct Entry {
    Vec3 center, axis_x, axis_y, normal;  // unit axes; normal: the way light passes
    float half_x = 0.0f, half_y = 0.0f, area = 0.0f;
    bool ellipse = false;
  };
  bool faces(const Entry& e, const Vec3& p) const;
  // Whether a point of e's plane lies inside its shape.
  bool inside(const Entry& e, const Vec3& x) const;
  // Whether the ray from p along wi (towards the world) leaves through e, and at which distance.
  bool hit(const Entry& e, const Vec3& p, const Vec3& wi, float* t) const;
  float entry_pdf(const Entry& e, const Vec3& p, const Vec3& wi) const;

  std::vector<Entry> portals_;
  std::vector<float> area_cdf_;  // running sums of the areas
  float total_area_ = 0.0f;
};

}  // namespace photon

#include "photon/scene/camera.h"

#include "photon/base/sampling.h"

namespace photon {

Ray generate_camera_ray(const Camera& camera, float film_x, float film_y, Vec2 lens_u) {
  const float x = camera.window_min_x + film_x * (camera.window_max_x - camera.window_min_x);
  const float y = camera.window_max_y - film_y * (camera.window_max_y - camera.window_min_y);
  const Transform& xf = camera.camera_to_world;  // rigid: see Camera::camera_to_world
  Ray ray;
  if (camera.projection == Projection::kPerspective && camera.aperture_radius <= 0.0f) {
    // Pinhole fast path: v = (x, y, -1) has axial component 1, so a clip distance d along the
    // view axis is t = d * |v| along the unit direction.
    const float len = std::sqrt(x * x + y * y + 1.0f);
    ray.origin = xf.column(3);
    ray.direction = xf.vector(Vec3(x, y, -1.0f)) * (1.0f / len);
    ray.tmin = camera.clip_start * len;
    ray.tmax = camera.clip_end * len;
  } else {
    Vec3 origin, direction;
    if (camera.projection == Projection::kPerspective) {
      origin = Vec3(0.0f);
      direction = normalize(Vec3(x, y, -1.0f));
    } else {
      origin = Vec3(x, y, 0.0f);
      direction = Vec3(0.0f, 0.0f, -1.0f);
    }
    if (camera.aperture_radius > 0.0f && camera.focus_distance > 0.0f) {
      // Thin lens (Kolb et al. 1995): rays through the aperture meet on the focal plane.
      const Vec2 d = sample_concentric_disk(lens_u);
      const Vec3 lens_point = origin + Vec3(d.x, d.y, 0.0f) * camera.aperture_radius;
      const Vec3 focus_point = origin + direction * (camera.focus_distance / -direction.z);
      origin = lens_point;
      direction = normalize(focus_point - lens_point);
    }
    const float axial = std::max(-direction.z, 1e-6f);  // cosine to the view axis
    ray.origin = xf.point(origin);
    ray.direction = xf.vector(direction);
    ray.tmin = camera.clip_start / axial;
    ray.tmax = camera.clip_end / axial;
  }
  if (!(ray.tmax > ray.tmin)) ray.tmax = INFINITY;
  return ray;
}

}  // namespace photon

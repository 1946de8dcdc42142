#include "photon/camera.h"

#include "photon/sampling.h"

namespace photon {

Ray generate_camera_ray(const Camera& camera, float film_x, float film_y, Vec2 lens_u) {
  const float x = camera.window_min_x + film_x * (camera.window_max_x - camera.window_min_x);
  const float y = camera.window_max_y - film_y * (camera.window_max_y - camera.window_min_y);
  Vec3 origin, direction;
  float axial;  // cos of the angle to the view axis, turns axial clip distances into ray t
  if (camera.projection == Projection::kPerspective) {
    origin = Vec3(0.0f);
    direction = normalize(Vec3(x, y, -1.0f));
    axial = -direction.z;
  } else {
    origin = Vec3(x, y, 0.0f);
    direction = Vec3(0.0f, 0.0f, -1.0f);
    axial = 1.0f;
  }
  if (camera.aperture_radius > 0.0f && camera.focus_distance > 0.0f) {
    // Thin lens (Kolb et al. 1995): rays through the aperture converge on the focal plane.
    const Vec2 d = sample_concentric_disk(lens_u);
    const Vec3 lens_point = origin + Vec3(d.x, d.y, 0.0f) * camera.aperture_radius;
    const Vec3 focus_point = origin + direction * (camera.focus_distance / axial);
    origin = lens_point;
    direction = normalize(focus_point - lens_point);
    axial = -direction.z;
  }
  Ray ray;
  ray.origin = camera.camera_to_world.point(origin);
  ray.direction = normalize(camera.camera_to_world.vector(direction));
  // Ray t is in world units; the camera matrix may carry scale, so measure the clip planes
  // after transforming the direction's length.
  const float world_scale = length(camera.camera_to_world.vector(direction));
  const float safe_axial = std::max(axial, 1e-6f);
  ray.tmin = camera.clip_start / safe_axial * world_scale;
  ray.tmax = camera.clip_end / safe_axial * world_scale;
  if (!(ray.tmax > ray.tmin)) ray.tmax = INFINITY;
  return ray;
}

}  // namespace photon

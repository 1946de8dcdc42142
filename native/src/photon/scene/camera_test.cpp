#include "photon/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "photon/testing/test_scenes.h"
#include "photon/testing/test_util.h"

namespace photon {
namespace camera_test {
namespace {

// A rotated and translated camera: its columns are right, up, back (view axis = -back), eye.
struct CameraBasis {
  Vec3 right, up, back, eye;
};

Camera make_rotated_camera(Projection projection) {
  // Unit quaternion rotation built by hand (axis (1, 2, 3) / |.|, angle 0.7 rad).
  const Vec3 axis = normalize(Vec3(1.0f, 2.0f, 3.0f));
  const float a = 0.7f, c = std::cos(a), s = std::sin(a), t = 1.0f - c;
  const float x = axis.x, y = axis.y, z = axis.z;
  const float rows[12] = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, 1.5f,
                          t * x * y + s * z, t * y * y + c,     t * y * z - s * x, -2.0f,
                          t * x * z - s * y, t * y * z + s * x, t * z * z + c,     0.75f};
  Camera cam;
  cam.projection = projection;
  cam.camera_to_world = Transform::from_rows(rows);
  // Deliberately asymmetric window (as with lens shift).
  cam.window_min_x = -0.3f;
  cam.window_max_x = 0.7f;
  cam.window_min_y = -0.2f;
  cam.window_max_y = 0.4f;
  cam.clip_start = 0.25f;
  cam.clip_end = 40.0f;
  return cam;
}

CameraBasis basis_of(const Camera& cam) {
  const Transform& m = cam.camera_to_world;
  return {m.column(0), m.column(1), m.column(2), m.column(3)};
}

// Camera-space window position of film coordinates (x right, y down).
Vec2 window_point(const Camera& cam, float fx, float fy) {
  return {cam.window_min_x + fx * (cam.window_max_x - cam.window_min_x),
          cam.window_max_y - fy * (cam.window_max_y - cam.window_min_y)};
}

TEST(Camera, RotatedCameraBasisIsOrthonormal) {
  const CameraBasis b = basis_of(make_rotated_camera(Projection::kPerspective));
  EXPECT_NEAR(length(b.right), 1.0f, 1e-5f);
  EXPECT_NEAR(length(b.up), 1.0f, 1e-5f);
  EXPECT_NEAR(dot(b.right, b.up), 0.0f, 1e-5f);
  EXPECT_TRUE(VecNear(cross(b.right, b.up), b.back, 1e-5f));
}

TEST(Camera, PerspectiveFilmCentreLooksDownTheViewAxis) {
  Camera cam = make_rotated_camera(Projection::kPerspective);
  cam.window_min_x = -0.5f;
  cam.window_max_x = 0.5f;
  cam.window_min_y = -0.3f;
  cam.window_max_y = 0.3f;
  const CameraBasis b = basis_of(cam);
  const Ray ray = generate_camera_ray(cam, 0.5f, 0.5f, Vec2(0.3f, 0.8f));
  EXPECT_TRUE(VecNear(ray.origin, b.eye, 1e-5f));
  EXPECT_TRUE(VecNear(ray.direction, -b.back, 1e-5f));
}

TEST(Camera, PerspectiveCornersMapToWindowCorners) {
  const Camera cam = make_rotated_camera(Projection::kPerspective);
  const CameraBasis b = basis_of(cam);
  for (float fx : {0.0f, 0.25f, 1.0f}) {
    for (float fy : {0.0f, 0.6f, 1.0f}) {
      const Ray ray = generate_camera_ray(cam, fx, fy, Vec2(0.5f, 0.5f));
      const Vec2 w = window_point(cam, fx, fy);
      const Vec3 expected = normalize(b.right * w.x + b.up * w.y - b.back);
      EXPECT_TRUE(VecNear(ray.origin, b.eye, 1e-5f));
      EXPECT_NEAR(length(ray.direction), 1.0f, 1e-5f);
      EXPECT_TRUE(VecNear(ray.direction, expected, 1e-5f)) << fx << " " << fy;
    }
  }
  // Top-left of the film is the window's (min_x, max_y) corner, bottom-right is (max_x, min_y).
  const Ray tl = generate_camera_ray(cam, 0.0f, 0.0f, Vec2(0.5f, 0.5f));
  const Vec3 d = tl.direction / dot(tl.direction, -b.back);  // back to the plane at distance 1
  EXPECT_NEAR(dot(d, b.right), cam.window_min_x, 1e-5f);
  EXPECT_NEAR(dot(d, b.up), cam.window_max_y, 1e-5f);
  const Ray br = generate_camera_ray(cam, 1.0f, 1.0f, Vec2(0.5f, 0.5f));
  const Vec3 e = br.direction / dot(br.direction, -b.back);
  EXPECT_NEAR(dot(e, b.right), cam.window_max_x, 1e-5f);
  EXPECT_NEAR(dot(e, b.up), cam.window_min_y, 1e-5f);
}

TEST(Camera, FilmYGoesDownwardsAndFilmXToTheRight) {
  for (Projection proj : {Projection::kPerspective, Projection::kOrthographic}) {
    const Camera cam = make_rotated_camera(proj);
    const CameraBasis b = basis_of(cam);
    auto up_of = [&](float fx, float fy) {
      const Ray r = generate_camera_ray(cam, fx, fy, Vec2(0.5f, 0.5f));
      return dot(r.origin + r.direction * 3.0f - b.eye, b.up);
    };
    auto right_of = [&](float fx, float fy) {
      const Ray r = generate_camera_ray(cam, fx, fy, Vec2(0.5f, 0.5f));
      return dot(r.origin + r.direction * 3.0f - b.eye, b.right);
    };
    EXPECT_GT(up_of(0.5f, 0.2f), up_of(0.5f, 0.8f));
    EXPECT_LT(right_of(0.2f, 0.5f), right_of(0.8f, 0.5f));
  }
}

TEST(Camera, OrthographicRaysAreParallelAndSpreadOverTheWindow) {
  const Camera cam = make_rotated_camera(Projection::kOrthographic);
  const CameraBasis b = basis_of(cam);
  for (float fx : {0.0f, 0.5f, 0.9f, 1.0f}) {
    for (float fy : {0.0f, 0.3f, 1.0f}) {
      const Ray ray = generate_camera_ray(cam, fx, fy, Vec2(0.1f, 0.9f));
      const Vec2 w = window_point(cam, fx, fy);
      EXPECT_TRUE(VecNear(ray.direction, -b.back, 1e-5f));
      EXPECT_TRUE(VecNear(ray.origin, b.eye + b.right * w.x + b.up * w.y, 1e-5f))
          << fx << " " << fy;
      EXPECT_NEAR(ray.tmin, cam.clip_start, 1e-5f);
      EXPECT_NEAR(ray.tmax, cam.clip_end, 1e-3f);
    }
  }
}

TEST(Camera, ClipDistancesAreMeasuredAlongTheViewAxis) {
  Camera cam = make_rotated_camera(Projection::kPerspective);
  const CameraBasis b = basis_of(cam);
  for (float aperture : {0.0f, 0.2f}) {
    cam.aperture_radius = aperture;
    cam.focus_distance = 3.0f;
    for (float fx : {0.0f, 0.5f, 0.83f, 1.0f}) {
      for (float fy : {0.0f, 0.5f, 1.0f}) {
        const Ray ray = generate_camera_ray(cam, fx, fy, Vec2(0.9f, 0.2f));
        const float axial = dot(ray.direction, -b.back);
        // The origin lies on the lens plane through the eye, so depth = t * axial cosine.
        EXPECT_NEAR(dot(ray.origin - b.eye, b.back), 0.0f, 1e-5f);
        EXPECT_NEAR(ray.tmin * axial, cam.clip_start, 1e-5f) << fx << " " << fy;
        EXPECT_NEAR(ray.tmax * axial, cam.clip_end, 1e-3f) << fx << " " << fy;
        if (fx != 0.5f || fy != 0.5f) EXPECT_GT(ray.tmin, cam.clip_start);
      }
    }
  }
}

TEST(Camera, ThinLensRaysConvergeOnTheFocalPlane) {
  for (Projection proj : {Projection::kPerspective, Projection::kOrthographic}) {
    Camera cam = make_rotated_camera(proj);
    cam.aperture_radius = 0.15f;
    cam.focus_distance = 4.0f;
    const CameraBasis b = basis_of(cam);
    Camera pinhole = cam;
    pinhole.aperture_radius = 0.0f;
    for (float fx : {0.1f, 0.5f, 0.95f}) {
      for (float fy : {0.05f, 0.5f, 0.7f}) {
        // Where the pinhole ray crosses the plane at depth focus_distance.
        const Ray p = generate_camera_ray(pinhole, fx, fy, Vec2(0.5f, 0.5f));
        const Vec3 focus =
            p.origin + p.direction * (cam.focus_distance / dot(p.direction, -b.back));
        float max_offset = 0.0f;
        for (int i = 0; i < 8; ++i) {
          for (int j = 0; j < 8; ++j) {
            const Vec2 u((i + 0.5f) / 8.0f, (j + 0.5f) / 8.0f);
            const Ray r = generate_camera_ray(cam, fx, fy, u);
            EXPECT_NEAR(length(r.direction), 1.0f, 1e-5f);
            // The ray starts on the aperture disc...
            const Vec3 offset = r.origin - p.origin;
            EXPECT_NEAR(dot(offset, b.back), 0.0f, 1e-5f);
            EXPECT_LE(length(offset), cam.aperture_radius * (1.0f + 1e-5f));
            max_offset = std::max(max_offset, length(offset));
            // ...and reaches the same point of the focal plane as every other lens sample.
            const float t =
                (cam.focus_distance - dot(r.origin - b.eye, -b.back)) / dot(r.direction, -b.back);
            EXPECT_TRUE(VecNear(r.origin + r.direction * t, focus, 2e-5f * (1.0f + t)))
                << "film " << fx << " " << fy << " lens " << u.x << " " << u.y;
          }
        }
        // The aperture is actually used: lens samples spread over most of its radius.
        EXPECT_GT(max_offset, 0.7f * cam.aperture_radius);
      }
    }
  }
}

TEST(Camera, LookAtCameraCentresTheTarget) {
  const Vec3 eye(1.0f, -4.0f, 2.0f), target(-0.5f, 1.0f, 0.3f);
  const float fov = 0.8f, aspect = 1.5f;
  const Camera cam = make_look_at_camera(eye, target, fov, aspect);
  const Ray centre = generate_camera_ray(cam, 0.5f, 0.5f, Vec2(0.5f, 0.5f));
  EXPECT_TRUE(VecNear(centre.origin, eye, 1e-5f));
  EXPECT_TRUE(VecNear(centre.direction, normalize(target - eye), 1e-5f));
  // The top and bottom edges of the film centre line are fov apart.
  const Ray top = generate_camera_ray(cam, 0.5f, 0.0f, Vec2(0.5f, 0.5f));
  const Ray bottom = generate_camera_ray(cam, 0.5f, 1.0f, Vec2(0.5f, 0.5f));
  EXPECT_NEAR(std::acos(dot(top.direction, bottom.direction)), fov, 1e-4f);
  EXPECT_GT(top.direction.z, bottom.direction.z);  // world +Z is up on the film
}

}  // namespace
}  // namespace camera_test
}  // namespace photon

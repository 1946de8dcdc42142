#include "photon/render/camera_clip_check.h"

#include <cstdio>

namespace photon {

std::string camera_clip_warning(const Camera& camera, const Accel& accel) {
  if (!(camera.clip_start > 0.0f) || camera.clip_start > kBlenderMinClipStart * 1.01f) return {};
  constexpr int kProbes = 16;  // a 16 x 16 grid of film points
  int clipped = 0;
  for (int j = 0; j < kProbes; ++j) {
    for (int i = 0; i < kProbes; ++i) {
      Ray ray =
          generate_camera_ray(camera, (i + 0.5f) / kProbes, (j + 0.5f) / kProbes, Vec2(0.5f, 0.5f));
      if (!(ray.tmin > 0.0f)) continue;
      ray.tmax = ray.tmin;
      ray.tmin = 0.0f;
      if (accel.occluded(ray, kVisibleCamera)) ++clipped;
    }
  }
  if (clipped == 0) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "Camera clip start %.3g m (Blender's minimum) hides the scene's nearest surfaces "
                "(%d of %d probe rays): the scene is too small for Blender's camera; scale it "
                "up",
                static_cast<double>(camera.clip_start), clipped, kProbes * kProbes);
  return text;
}

}  // namespace photon

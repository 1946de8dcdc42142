#include "photon/film/camera_sample.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace photon {

float finite_average(float sum, float inv_spp) {
  const float v = sum * inv_spp;
  return std::isnan(v) ? 0.0f : std::clamp(v, -FLT_MAX, FLT_MAX);
}

Ray camera_sample_ray(const PixelFilter& filter, const Camera& camera, int full_width,
                      int full_height, int px, int py, Sampler& sampler) {
  const Vec2 jitter = filter.sample(sampler.get_2d());
  const Vec2 lens = sampler.get_2d();
  // Times the reciprocal, not divided: the reference images depend on these exact bits.
  const float inv_w = 1.0f / full_width, inv_h = 1.0f / full_height;
  return generate_camera_ray(camera, (px + jitter.x) * inv_w, (py + jitter.y) * inv_h, lens);
}

}  // namespace photon

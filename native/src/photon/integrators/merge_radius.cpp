#include "photon/integrators/merge_radius.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "photon/render/accel.h"
#include "photon/scene/camera.h"

namespace photon {
namespace {

// A tenth of a pixel: the pixel filter blurs finer detail anyway.
constexpr float kMinFootprints = 0.1f;
// A quarter of the scene's bounding radius.
constexpr float kMaxSceneFraction = 0.25f;

std::string length_text(float x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", static_cast<double>(x));
  return buffer;
}

}  // namespace

float median_pixel_footprint(const RenderContext& context, const FilmFrame& f) {
  const Camera& camera = f.camera;
  const float inv_w = 1.0f / f.full_width, inv_h = 1.0f / f.full_height;
  const int step = std::max(1, std::max(f.full_width, f.full_height) / 64);
  std::vector<float> seen;
  for (int py = 0; py < f.full_height; py += step)
    for (int px = 0; px < f.full_width; px += step) {
      const Vec2 lens(0.5f, 0.5f);
      const Ray a = generate_camera_ray(camera, (px + 0.5f) * inv_w, (py + 0.5f) * inv_h, lens);
      const Ray b = generate_camera_ray(camera, (px + 1.5f) * inv_w, (py + 0.5f) * inv_h, lens);
      Hit hit;
      if (!context.accel->intersect(a, kVisibleCamera, &hit)) continue;
      const float d = length((b.origin + hit.t * b.direction) - (a.origin + hit.t * a.direction));
      if (std::isfinite(d) && d > 0.0f) seen.push_back(d);
    }
  if (seen.empty()) return 0.0f;
  std::nth_element(seen.begin(), seen.begin() + seen.size() / 2, seen.end());
  return seen[seen.size() / 2];
}

RadiusRange meaningful_radius_range(float footprint, float scene_radius, float automatic) {
  RadiusRange range;
  range.scene_radius = scene_radius;
  range.min = kMinFootprints * footprint;
  range.max = kMaxSceneFraction * scene_radius;
  if (automatic > 0.0f) {
    range.min = std::min(range.min, automatic);
    range.max = std::max(range.max, automatic);
  }
  if (!(range.max > 0.0f) || !std::isfinite(range.max)) range.max = automatic;
  range.min = std::min(range.min, range.max);
  return range;
}

float clamp_radius(const char* setting, float requested, const RadiusRange& range,
                   std::string* warning) {
  if (requested < range.min) {
    if (warning)
      *warning = std::string(setting) + " = " + length_text(requested) +
                 " is smaller than a tenth of a pixel at the depth the camera sees, so almost no "
                 "photon would ever be gathered: using " +
                 length_text(range.min);
    return range.min;
  }
  if (range.max > 0.0f && requested > range.max) {
    if (warning)
      *warning = std::string(setting) + " = " + length_text(requested) +
                 " is wider than a quarter of the scene (bounding radius " +
                 length_text(range.scene_radius) +
                 "), which blurs the light across whole objects and reads most photons at "
                 "every pixel: using " +
                 length_text(range.max);
    return range.max;
  }
  return requested;
}

}  // namespace photon

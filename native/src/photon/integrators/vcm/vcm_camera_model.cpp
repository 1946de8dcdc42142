#include "photon/integrators/vcm/vcm_camera_model.h"

#include <cmath>

namespace photon {

VcmCamera::VcmCamera(const FilmFrame& frame, const FilmOptions& film)
    : camera_(frame.camera),
      filter_(film.filter_type, film.filter_width),
      type_(filter_.type()),
      width_(filter_.width()),
      wmin_x_(frame.camera.window_min_x),
      wmax_x_(frame.camera.window_max_x),
      wmin_y_(frame.camera.window_min_y),
      wmax_y_(frame.camera.window_max_y),
      clip_start_(frame.camera.clip_start),
      clip_end_(frame.camera.clip_end),
      full_width_(frame.full_width),
      full_height_(frame.full_height) {
  const Camera& camera = frame.camera;
  supported_ = camera.projection == Projection::kPerspective && camera.aperture_radius <= 0.0f;
  const Transform& xf = camera.camera_to_world;  // rigid
  position_ = xf.column(3);
  right_ = normalize(xf.vector(Vec3(1.0f, 0.0f, 0.0f)));
  up_ = normalize(xf.vector(Vec3(0.0f, 1.0f, 0.0f)));
  forward_ = normalize(xf.vector(Vec3(0.0f, 0.0f, -1.0f)));
  const double sx = (static_cast<double>(wmax_x_) - wmin_x_) / full_width_;
  const double sy = (static_cast<double>(wmax_y_) - wmin_y_) / full_height_;
  inv_pixel_area_ = static_cast<float>(1.0 / (sx * sy));
  if (!(sx > 0.0) || !(sy > 0.0) || !std::isfinite(inv_pixel_area_)) supported_ = false;
  // The box of PixelFilter::sample_1d spans `width` pixels; the smooth filters their support,
  // normalised by the midpoint rule on the cells the sampler's own table uses.
  if (type_ == PixelFilterType::kBox) {
    half_support_ = 0.5f * width_;
    inv_integral_ = 1.0f / width_;
  } else {
    half_support_ = 0.5f * pixel_filter_support(type_, width_);
    const int cells = PixelFilter::kCells;
    const double cell = 2.0 * half_support_ / cells;
    double total = 0.0;
    for (int k = 0; k < cells; ++k)
      total +=
          pixel_filter_value(type_, width_, static_cast<float>(-half_support_ + (k + 0.5) * cell));
    inv_integral_ = static_cast<float>(1.0 / (total * cell));
  }
}

float VcmCamera::filter_1d(float x) const {
  if (!(std::fabs(x) <= half_support_)) return 0.0f;
  if (type_ == PixelFilterType::kBox) return inv_integral_;
  return pixel_filter_value(type_, width_, x) * inv_integral_;
}

bool VcmCamera::project(const Vec3& p, Vec2* raster, float* cos_axis, float* distance) const {
  const Vec3 v = p - position_;
  const float depth = dot(v, forward_);
  if (!(depth >= clip_start_) || !(depth <= clip_end_)) return false;
  const float fx = dot(v, right_) / depth, fy = dot(v, up_) / depth;
  const float rx = (fx - wmin_x_) / (wmax_x_ - wmin_x_) * full_width_;
  const float ry = (wmax_y_ - fy) / (wmax_y_ - wmin_y_) * full_height_;
  const float margin = half_support_ + 0.5f;
  if (!(rx > -margin && rx < full_width_ + margin && ry > -margin && ry < full_height_ + margin))
    return false;
  *raster = Vec2(rx, ry);
  *distance = length(v);
  *cos_axis = depth / *distance;
  return *distance > 0.0f;
}

}  // namespace photon

// The camera as VCM's light tracing sees it (Georgiev et al. 2012 strategy t = 1; Veach 1997
// sec. 10.2): a pinhole perspective camera whose pixels estimate the image convolved with the
// film's pixel filter. Camera subpaths importance sample the filter (pixel_filter.h), so a
// camera sample of pixel j at raster point x has density f_j(x) = g(dx) g(dy) / G^2 (g the 1D
// filter, G its integral, (dx, dy) = x - centre of j) per unit raster area; a light subpath
// vertex seen at raster point x adds to every pixel j whose filter covers x, weighted by f_j(x),
// and each pixel's MIS weights use its own f_j, so every strategy estimates the same pixel value.
#pragma once

#include "photon/base/math.h"
#include "photon/film/film.h"
#include "photon/scene/pixel_filter.h"

namespace photon {

class VcmCamera {
 public:
  // The camera of `frame`, whose pixels the film's filter covers.
  VcmCamera(const FilmFrame& frame, const FilmOptions& film);
  // Light tracing needs a camera position: pinhole perspective only (no orthographic, no depth
  // of field).
  bool supported() const { return supported_; }
  Vec3 position() const { return position_; }
  // Raster position of world point p (x right, y down, in pixels of the full frame), the
  // cosine of the direction to p with the view axis and the distance; false if p is behind the
  // camera, outside the clipping range or too far outside the frame for any pixel's filter.
  bool project(const Vec3& p, Vec2* raster, float* cos_axis, float* distance) const;
  // Solid-angle density of a camera ray direction per unit raster density: 1 / (sx sy cos^3),
  // (sx, sy) the pixel's size on the image plane at distance 1.
  float raster_to_solid_angle(float cos_axis) const {
    return inv_pixel_area_ / (cos_axis * cos_axis * cos_axis);
  }
  float cos_axis(const Vec3& direction) const { return dot(direction, forward_); }
  // f_j of an offset (dx, dy) from a pixel's centre, in pixels.
  float filter_pdf(float dx, float dy) const { return filter_1d(dx) * filter_1d(dy); }
  float filter_half_support() const { return half_support_; }
  const PixelFilter& filter() const { return filter_; }
  const Camera& camera() const { return camera_; }
  int full_width() const { return full_width_; }
  int full_height() const { return full_height_; }

 private:
  float filter_1d(float x) const;

  Camera camera_;
  PixelFilter filter_;
  PixelFilterType type_;
  float width_;
  float half_support_ = 0.5f;
  float inv_integral_ = 1.0f;
  bool supported_ = false;
  Vec3 position_, right_, up_, forward_;
  float wmin_x_, wmax_x_, wmin_y_, wmax_y_;
  float clip_start_, clip_end_;
  int full_width_, full_height_;
  float inv_pixel_area_ = 1.0f;
};

}  // namespace photon

// The film (pbrt-v4's Film, Cycles' render buffers): the pixels an integrator renders into. It
// owns what every integrator shares about a pixel, so each is written once:
//  - which pixels: a camera's frame and the rectangle of it rendered (a render border, a farm
//    band), optionally every step-th pixel of it (a coarse first look);
//  - the camera sample of a pixel (the pixel filter's jitter, then the lens);
//  - accumulation: per pixel the sum of its samples' light and coverage, and of the light
//    passes, with the coverage rule for holdouts and a transparent film;
//  - the passes by name (the light passes and the data passes, as Blender registers them);
//  - resolving sums into pixel values (the exposure, a finite average).
// A pixel is written by one thread at a time; the film never decides the order of samples, so
// the same samples give the same bits whichever thread or tile added them.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "photon/film/camera_sample.h"
#include "photon/film/data_pass_settings.h"
#include "photon/film/pass_layout.h"
#include "photon/film/radiance_sample.h"

namespace photon {

// The pixels a film holds: a camera's full_width x full_height frame, of which the rectangle
// [x0, x1) x [y0, y1) (y downwards) is rendered, every step-th pixel of every step-th row.
struct FilmFrame {
  Camera camera;
  int full_width = 64, full_height = 64;
  int x0 = 0, y0 = 0, x1 = 64, y1 = 64;
  int step = 1;
};

// How samples become pixels (Cycles' Film panel) and which passes the film keeps.
struct FilmOptions {
  PixelFilterType filter_type = PixelFilterType::kBox;
  float filter_width = 1.0f;
  float exposure = 1.0f;  // scales light: Combined, the light passes and Emit
  bool transparent_background = false;
  bool light_passes = false;
  // Spectral mode: a pixel whose colour lies outside the Rec.709 gamut (a deep red blackbody,
  // a spectral line) averages to negative channels; resolved pixels are moved into the gamut
  // keeping their luminance (into_rec709_gamut).
  bool into_gamut = false;
  DataPassSettings data_passes;
};

// Film pixels [x, x + width) x [y, y + height), relative to the film's first pixel.
struct FilmRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// A pass of a resolved rectangle: `channels` floats per pixel, rows top first.
struct PassImage {
  std::string name;  // as Blender registers it: "Photon Direct", "Depth", "CryptoObject00", ...
  int channels = 0;
  std::string channel_ids;  // "RGB", "Z", "RGBA", ...
  std::vector<float> pixels;
};

class Film {
 public:
  Film(const FilmFrame& frame, const FilmOptions& options);

  const FilmFrame& frame() const { return frame_; }
  const FilmOptions& options() const { return options_; }
  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return static_cast<size_t>(width_) * height_; }
  size_t index(int col, int row) const { return static_cast<size_t>(row) * width_ + col; }
  // The frame pixel that film pixel (col, row) stands for, and its index in the whole frame
  // (which seeds its samples, so a band of a frame renders the same bits as the whole frame).
  int frame_x(int col) const { return frame_.x0 + col * frame_.step; }
  int frame_y(int row) const { return frame_.y0 + row * frame_.step; }
  uint64_t frame_pixel(int col, int row) const {
    return static_cast<uint64_t>(frame_y(row)) * frame_.full_width + frame_x(col);
  }

  // The camera ray of the sample `sampler` (seeded with (seed, pixel, sample)) through frame
  // pixel (px, py).
  Ray camera_ray(int px, int py, Sampler& sampler) const {
    return camera_sample_ray(filter_, frame_.camera, frame_.full_width, frame_.full_height, px, py,
                             sampler);
  }

  // The share of its pixel a sample covers: its alpha with a transparent film, else all of it
  // (the background is opaque too, as in Blender's engines); holdouts take their share out
  // either way (Cycles).
  float coverage(float alpha, float holdout) const;

  // Adds a sample to a pixel: its light, its coverage and, when the film keeps them, its light
  // passes. A sample whose light is not finite is dropped and counted (false).
  bool add_sample(size_t pixel, const RadianceSample& sample);
  // Adds light and coverage only, for samples whose light is not split into passes.
  bool add_light(size_t pixel, const Vec3& radiance, float coverage);
  // Replaces a pixel's sums, for integrators that keep their own per-pixel estimates (SPPM):
  // `light_passes` holds kPassCount sums, or is null.
  void set_sums(size_t pixel, const Vec3& light, float coverage, const Vec3* light_passes);
  void count_non_finite(uint64_t n) { non_finite_.fetch_add(n, std::memory_order_relaxed); }
  uint64_t non_finite() const { return non_finite_.load(); }
  // Zero sums (a restart).
  void clear();

  // Adaptive sampling (Cycles' Noise Threshold): pixels whose estimate has converged stop taking
  // samples. Once enabled the film counts each pixel's samples (pixels then resolve by their own
  // count) and keeps a second sum of the even-numbered samples, whose difference from the whole
  // estimates the pixel's error (film_adaptive.cpp).
  void enable_adaptive_sampling();
  bool adaptive() const { return !pixel_samples_.empty(); }
  // Whether the pixel still takes samples (always, without adaptive sampling).
  bool pixel_active(size_t pixel) const { return active_.empty() || active_[pixel] != 0; }
  // add_sample for sample number `k` of an adaptive film's pixel.
  bool add_adaptive_sample(size_t pixel, const RadianceSample& sample, int k);
  // Decides which pixels go on after a round of samples, as Cycles does: a pixel whose relative
  // error is below `threshold` is converged (and stays so), then every pixel next to one that is
  // not keeps sampling. Returns how many pixels go on. Deterministic: it reads only the sums.
  size_t update_convergence(float threshold);
  // Samples the film's pixels took together (adaptive films only).
  uint64_t total_samples() const;

  // The data passes: data_floats() resolved floats per pixel (pass_layout.h), written a row at a
  // time by whoever traces them.
  int data_floats() const { return data_floats_; }
  float* data_row(int row) {
    return data_.data() + static_cast<size_t>(row) * width_ * data_floats_;
  }

  // Calls f(col, row) for every film pixel, rows spread over the calling TBB arena, each pixel
  // by one thread; stops between rows once `cancel` is set. For integrators that refine every
  // pixel once per iteration (SPPM, VCM); the pixel integrators' loop is pixel_integrator.h's.
  template <class F>
  void for_each_pixel(const std::atomic<bool>& cancel, F&& f) const {
    tbb::parallel_for(tbb::blocked_range<int>(0, height_, 1),
                      [&](const tbb::blocked_range<int>& rows) {
                        for (int row = rows.begin(); row != rows.end(); ++row) {
                          if (cancel.load(std::memory_order_relaxed)) return;
                          for (int col = 0; col < width_; ++col) f(col, row);
                        }
                      });
  }

  // Pixel values of `rect` after `samples` samples: RGBA rows (top first, 4 floats a pixel).
  void resolve_rgba(const FilmRect& rect, int samples, float* rgba) const;
  // Every pass the film keeps, resolved for `rect` after `samples` samples: the light passes,
  // then the data passes and Cryptomatte layers.
  std::vector<PassImage> resolve_passes(const FilmRect& rect, int samples) const;

 private:
  // 1 / the samples a pixel's sums hold after `samples` passes.
  float inv_samples(size_t pixel, int samples) const {
    const uint32_t n = adaptive() ? pixel_samples_[pixel] : static_cast<uint32_t>(samples);
    return 1.0f / static_cast<float>(std::max<uint32_t>(n, 1));
  }
  // The pixel's gamut_blend (1 without into_gamut), and a sum resolved and moved by it.
  float pixel_gamut_blend(size_t pixel, float colour_scale) const;
  Vec3 resolved_colour(const Vec3& sum, float colour_scale, float blend) const;

  FilmFrame frame_;
  FilmOptions options_;
  PixelFilter filter_;
  int width_ = 0, height_ = 0;
  int data_floats_ = 0;
  std::vector<float> sums_;      // per pixel: light RGB, then coverage
  std::vector<Vec3> pass_sums_;  // per pixel: kPassCount light passes (with light_passes)
  std::vector<float> data_;      // per pixel: data_floats_ resolved data-pass floats
  // Adaptive sampling, per pixel: samples taken, the light of the even-numbered ones, whether it
  // has converged and whether it still takes samples.
  std::vector<uint32_t> pixel_samples_;
  std::vector<Vec3> even_sums_;
  std::vector<uint8_t> converged_, active_;
  std::atomic<uint64_t> non_finite_{0};
};

// How far a colour of luminance Y = luminance(c) > 0 must move towards grey (Y, Y, Y) to have no
// negative channel: c' = Y + t (c - Y) with t = Y / (Y - min(c)) when a channel is negative, 1
// when none is, 0 when Y <= 0. The hue stays, the saturation is the gamut's largest at that hue
// (a luminance-keeping clip). Linear in c for a given t, so the light passes, moved by their
// pixel's t, still sum to the pixel (unless one is more saturated than the pixel: it is clipped
// at 0).
float gamut_blend(const Vec3& c);
inline Vec3 blend_towards_grey(const Vec3& c, float t) {
  const float y = luminance(c);
  return Vec3(y) + (c - Vec3(y)) * t;
}

// The film of a frame rendered with `camera` at full_width x full_height, of its rectangle
// [x0, x1) x [y0, y1).
FilmFrame film_frame(const Camera& camera, int full_width, int full_height, int x0, int y0, int x1,
                     int y1, int step = 1);

}  // namespace photon

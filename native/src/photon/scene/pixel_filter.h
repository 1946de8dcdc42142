// The pixel filter: where in and around a pixel its camera samples land. As in Cycles, the filter
// is importance sampled rather than splatted: a sample's offset from the pixel centre is drawn per
// axis from the normalized 1D filter by inverting its tabulated CDF, so every sample keeps
// weight 1, a pixel's value depends only on its own samples (tile and thread independent), and the
// pixel estimates the image convolved with the separable filter f(x) f(y).
#pragma once

#include <cstdint>
#include <vector>

#include "photon/base/math.h"

namespace photon {

enum class PixelFilterType : uint8_t { kBox, kGaussian, kBlackmanHarris };

constexpr float kMinFilterWidth = 0.01f, kMaxFilterWidth = 10.0f;  // Cycles' range, in pixels

// `width` brought into [kMinFilterWidth, kMaxFilterWidth]; NaN becomes 1 (one pixel).
float clamp_filter_width(float width);

// Full width in pixels of the filter's support for the user's `width`. Cycles widens the support
// of its smooth filters so `width` keeps a box-like meaning: Gaussian spans 3 widths, Blackman-
// Harris 2.
float pixel_filter_support(PixelFilterType type, float width);

// The (unnormalized) 1D filter at offset `x` pixels from the pixel centre, 0 outside the support.
// Cycles' definitions (film.cpp) over the support s: Box 1; Gaussian exp(-2 (6 x / s)^2), i.e.
// sigma = width / 4 cut at 6 sigma; Blackman-Harris (Harris 1978, eq. 33, four terms) with
// phase 2 pi (x / s + 1/2).
float pixel_filter_value(PixelFilterType type, float width, float x);

class PixelFilter {
 public:
  // The width is clamped as clamp_filter_width does.
  PixelFilter(PixelFilterType type, float width);

  // The sample's position in its pixel, (0.5, 0.5) at the centre, from a uniform u in [0, 1)^2.
  // Box keeps its exact historic mapping (u itself at width 1), so box images do not change.
  Vec2 sample(Vec2 u) const { return {sample_1d(u.x), sample_1d(u.y)}; }
  float sample_1d(float u) const;

  PixelFilterType type() const { return type_; }
  float width() const { return width_; }

  // Cells of the tabulated CDF. Cycles interpolates a 1024-entry table of the inverse CDF
  // linearly, which spreads the first and last 1/1023 of the probability evenly over the far
  // tails (a Gaussian's sigma comes out ~1% wide); inverting the CDF per sample by binary search
  // (13 steps) is exact up to the cell size.
  static constexpr int kCells = 8192;

 private:
  PixelFilterType type_;
  float width_;
  double half_support_ = 0.0, cell_ = 0.0;
  std::vector<double> cdf_;  // kCells + 1 entries from 0 to 1; empty for Box
};

}  // namespace photon

#include "photon/scene/pixel_filter.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {
constexpr double kPiD = 3.14159265358979323846;
}  // namespace

float clamp_filter_width(float width) {
  if (std::isnan(width)) return 1.0f;
  return std::clamp(width, kMinFilterWidth, kMaxFilterWidth);
}

float pixel_filter_support(PixelFilterType type, float width) {
  width = clamp_filter_width(width);
  switch (type) {
    case PixelFilterType::kGaussian:
      return 3.0f * width;
    case PixelFilterType::kBlackmanHarris:
      return 2.0f * width;
    case PixelFilterType::kBox:
      break;
  }
  return width;
}

float pixel_filter_value(PixelFilterType type, float width, float x) {
  const double s = pixel_filter_support(type, width);
  if (!(std::abs(x) <= 0.5 * s)) return 0.0f;
  switch (type) {
    case PixelFilterType::kGaussian: {
      const double v = x * 6.0 / s;
      return static_cast<float>(std::exp(-2.0 * v * v));
    }
    case PixelFilterType::kBlackmanHarris: {
      const double v = 2.0 * kPiD * (x / s + 0.5);
      return static_cast<float>(0.35875 - 0.48829 * std::cos(v) + 0.14128 * std::cos(2.0 * v) -
                                0.01168 * std::cos(3.0 * v));
    }
    case PixelFilterType::kBox:
      break;
  }
  return 1.0f;
}

PixelFilter::PixelFilter(PixelFilterType type, float width)
    : type_(type), width_(clamp_filter_width(width)) {
  if (type_ == PixelFilterType::kBox) return;  // uniform: no table needed
  // The CDF of the filter over its support, integrated by the midpoint rule on kCells cells.
  half_support_ = 0.5 * pixel_filter_support(type_, width_);
  cell_ = 2.0 * half_support_ / kCells;
  cdf_.assign(kCells + 1, 0.0);
  for (int k = 0; k < kCells; ++k)
    cdf_[k + 1] =
        cdf_[k] +
        pixel_filter_value(type_, width_, static_cast<float>(-half_support_ + (k + 0.5) * cell_));
  const double total = cdf_[kCells];
  for (double& c : cdf_) c /= total;
  cdf_[kCells] = 1.0;
}

float PixelFilter::sample_1d(float u) const {
  if (type_ == PixelFilterType::kBox)  // a box of that width around the pixel's centre
    return width_ == 1.0f ? u : 0.5f + (u - 0.5f) * width_;
  // Inverts the CDF exactly: the cell holding u, then linearly within it (the filter is taken
  // as constant over a cell, 1/8192 of the support).
  const double v = std::clamp(static_cast<double>(u), 0.0, 1.0);
  const int k =
      std::clamp(static_cast<int>(std::upper_bound(cdf_.begin(), cdf_.end(), v) - cdf_.begin()) - 1,
                 0, kCells - 1);
  const double mass = cdf_[k + 1] - cdf_[k];
  const double t = mass > 0.0 ? std::clamp((v - cdf_[k]) / mass, 0.0, 1.0) : 0.5;
  return static_cast<float>(0.5 - half_support_ + (k + t) * cell_);
}

}  // namespace photon

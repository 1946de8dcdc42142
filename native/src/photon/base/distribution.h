// A discrete distribution over n items proportional to non-negative weights, sampled by
// inverting its CDF with binary search (pbrt-v4's PiecewiseConstant1D, discrete case).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace photon {

class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(const std::vector<double>& weights) {
    cdf_.resize(weights.size() + 1, 0.0);
    for (size_t i = 0; i < weights.size(); ++i) cdf_[i + 1] = cdf_[i] + std::max(weights[i], 0.0);
    total_ = cdf_.back();
  }
  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  bool empty() const { return !(total_ > 0.0); }
  float probability(size_t i) const { return static_cast<float>((cdf_[i + 1] - cdf_[i]) / total_); }
  // Picks an item for u in [0, 1); `remapped` (optional) receives u rescaled to [0, 1) inside
  // the item's interval, so one random number can serve two decisions.
  size_t sample(float u, float* remapped = nullptr) const {
    const double target = static_cast<double>(u) * total_;
    size_t i =
        static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
    i = std::clamp<size_t>(i, 1, size()) - 1;
    // Skip zero-weight items that upper_bound can land on at interval ends.
    while (i + 1 < size() && cdf_[i + 1] <= cdf_[i]) ++i;
    if (remapped) {
      const double width = cdf_[i + 1] - cdf_[i];
      const double r = width > 0.0 ? (target - cdf_[i]) / width : 0.0;
      *remapped = std::clamp(static_cast<float>(r), 0.0f, 0.99999994f);
    }
    return i;
  }

 private:
  std::vector<double> cdf_;
  double total_ = 0.0;
};

}  // namespace photon

// Adaptive sampling on the film, as Cycles does it (its kernel's adaptive_sampling.h): per pixel
// the error measure of Dammertz et al. 2010 ("A hierarchical automatic stopping condition for
// Monte Carlo global illumination", section 2.1), applied per pixel rather than per tile. The
// estimate I of all samples is compared with A, twice the sum of the even-numbered ones, which
// holds the same light from half the samples:
//   error = (|I.r - A.r| + |I.g - A.g| + |I.b - A.b|) / N  /  (1e-4 + sqrt((I.r + I.g + I.b) / N))
// (N the pixel's samples), and a pixel is converged when error < threshold. A converged pixel's
// neighbours (a 3 x 3 box, filtered along rows then columns) keep sampling while it is not: the
// measure is noisy itself, and a lone pixel stopped among noisy ones would show as a dot.
#include <atomic>
#include <cmath>
#include <vector>

#include "photon/base/check.h"
#include "photon/film/film.h"

namespace photon {

void Film::enable_adaptive_sampling() {
  pixel_samples_.assign(pixel_count(), 0u);
  even_sums_.assign(pixel_count(), Vec3(0.0f));
  converged_.assign(pixel_count(), 0);
  active_.assign(pixel_count(), 1);
}

bool Film::add_adaptive_sample(size_t pixel, const RadianceSample& sample, int k) {
  DCHECK(adaptive());
  // A sample dropped for not being finite counts as a black one, as without adaptive sampling.
  ++pixel_samples_[pixel];
  if (!add_sample(pixel, sample)) return false;
  if (k % 2 == 0) even_sums_[pixel] += sample.radiance();
  return true;
}

size_t Film::update_convergence(float threshold) {
  CHECK(adaptive());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pixel_count()), [&](const auto& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      if (converged_[p] || pixel_samples_[p] == 0) continue;
      const float inv_n = 1.0f / static_cast<float>(pixel_samples_[p]);
      const float* s = &sums_[4 * p];
      const Vec3 a = even_sums_[p] * 2.0f;
      const float difference =
          (std::fabs(s[0] - a.x) + std::fabs(s[1] - a.y) + std::fabs(s[2] - a.z)) * inv_n;
      const float normalize = std::sqrt(std::max(s[0] + s[1] + s[2], 0.0f) * inv_n);
      converged_[p] = difference / (1e-4f + normalize) < threshold;
    }
  });
  // A pixel samples on when it or a neighbour along its row, then along its column, has not
  // converged; one kept on is judged again after its next samples (Cycles clears its flag).
  std::vector<uint8_t> along_rows(pixel_count());
  tbb::parallel_for(0, height_, [&](int row) {
    for (int col = 0; col < width_; ++col) {
      bool on = !converged_[index(col, row)];
      if (col > 0) on = on || !converged_[index(col - 1, row)];
      if (col + 1 < width_) on = on || !converged_[index(col + 1, row)];
      along_rows[index(col, row)] = on;
    }
  });
  std::atomic<size_t> active{0};
  tbb::parallel_for(0, height_, [&](int row) {
    size_t n = 0;
    for (int col = 0; col < width_; ++col) {
      bool on = along_rows[index(col, row)];
      if (row > 0) on = on || along_rows[index(col, row - 1)];
      if (row + 1 < height_) on = on || along_rows[index(col, row + 1)];
      active_[index(col, row)] = on;
      converged_[index(col, row)] = !on;  // a pixel kept on is judged again next time
      n += on;
    }
    active += n;
  });
  return active.load();
}

uint64_t Film::total_samples() const {
  uint64_t n = 0;
  for (uint32_t s : pixel_samples_) n += s;
  return n;
}

}  // namespace photon

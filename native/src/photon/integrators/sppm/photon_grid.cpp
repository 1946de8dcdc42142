#include "photon/integrators/sppm/photon_grid.h"

#include <algorithm>

namespace photon {

PhotonGrid::PhotonGrid(std::vector<SppmPhoton> photons, float cell_size)
    : cell_size_(cell_size > 0.0f && std::isfinite(cell_size) ? cell_size : 1.0f),
      inv_cell_(1.0f / cell_size_) {
  uint32_t table = 1;
  while (table < photons.size() && table < (1u << 30)) table <<= 1;
  mask_ = table - 1;
  // Stable counting sort by bucket: a bucket keeps its photons in trace order.
  std::vector<uint32_t> buckets(photons.size());
  start_.assign(static_cast<size_t>(table) + 1, 0);
  for (size_t i = 0; i < photons.size(); ++i) {
    buckets[i] = bucket(cell_of(photons[i].p));
    ++start_[buckets[i] + 1];
  }
  for (size_t b = 0; b < table; ++b) start_[b + 1] += start_[b];
  std::vector<uint32_t> next(start_.begin(), start_.end() - 1);
  photons_.resize(photons.size());
  for (size_t i = 0; i < photons.size(); ++i) photons_[next[buckets[i]]++] = photons[i];
}

}  // namespace photon

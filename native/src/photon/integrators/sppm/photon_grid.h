// A hashed uniform grid over one iteration's photons (after pbrt-v4's SPPM grid, which hashes
// visible points instead): cells of a fixed size hashed into a table as large as the photon
// count, built by a stable counting sort. A query visits the cells overlapping its sphere in a
// fixed order and, within a cell, photons in their trace order, so every visible point sums its
// photons in one order whatever the threads do (SPPM's determinism rests on it).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "photon/integrators/sppm/sppm_photons.h"

namespace photon {

class PhotonGrid {
 public:
  PhotonGrid() = default;
  // `cell_size` > 0: queries of radius up to cell_size / 2 visit at most 2 x 2 x 2 cells.
  PhotonGrid(std::vector<SppmPhoton> photons, float cell_size);

  size_t size() const { return photons_.size(); }
  float cell_size() const { return cell_size_; }
  // Bytes held: the photons and the table.
  size_t memory_bytes() const {
    return photons_.capacity() * sizeof(SppmPhoton) + start_.capacity() * sizeof(uint32_t);
  }

  // Calls f(photon) for every photon within `radius` of `p`, in a fixed order.
  template <typename F>
  void for_each_within(const Vec3& p, float radius, F&& f) const;

 private:
  struct Cell {
    int32_t x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  Cell cell_of(const Vec3& p) const;
  uint32_t bucket(const Cell& c) const;

  std::vector<SppmPhoton> photons_;  // sorted by bucket, trace order within a bucket
  std::vector<uint32_t> start_;      // bucket b holds photons_[start_[b], start_[b + 1])
  float cell_size_ = 1.0f, inv_cell_ = 1.0f;
  uint32_t mask_ = 0;  // table size - 1 (a power of two)
};

template <typename F>
void PhotonGrid::for_each_within(const Vec3& p, float radius, F&& f) const {
  if (photons_.empty() || !(radius > 0.0f)) return;
  const float r2 = radius * radius;
  const auto visit = [&](const SppmPhoton& ph) {
    const Vec3 d = ph.p - p;
    if (dot(d, d) <= r2) f(ph);
  };
  const Cell lo = cell_of(p - Vec3(radius)), hi = cell_of(p + Vec3(radius));
  const double cells = (static_cast<double>(hi.x) - lo.x + 1) *
                       (static_cast<double>(hi.y) - lo.y + 1) *
                       (static_cast<double>(hi.z) - lo.z + 1);
  if (cells > static_cast<double>(photons_.size())) {
    // A sphere over more cells than there are photons: reading them all is cheaper.
    for (const SppmPhoton& ph : photons_) visit(ph);
    return;
  }
  for (int32_t z = lo.z; z <= hi.z; ++z)
    for (int32_t y = lo.y; y <= hi.y; ++y)
      for (int32_t x = lo.x; x <= hi.x; ++x) {
        const Cell c{x, y, z};
        const uint32_t b = bucket(c);
        // Other cells share the bucket: only this cell's photons count, so none is seen twice.
        for (uint32_t i = start_[b]; i < start_[b + 1]; ++i)
          if (cell_of(photons_[i].p) == c) visit(photons_[i]);
      }
}

inline PhotonGrid::Cell PhotonGrid::cell_of(const Vec3& p) const {
  // Clamped so a far-away point (or a tiny cell) cannot overflow the integer cell index.
  const auto index = [this](float v) {
    const float c = std::floor(v * inv_cell_);
    return static_cast<int32_t>(std::fmin(std::fmax(c, -1073741824.0f), 1073741824.0f));
  };
  return {index(p.x), index(p.y), index(p.z)};
}

inline uint32_t PhotonGrid::bucket(const Cell& c) const {
  // Teschner et al. 2003, "Optimized Spatial Hashing for Collision Detection of Deformable
  // Objects" (pbrt-v4's SPPM grid hash).
  const uint32_t h = (static_cast<uint32_t>(c.x) * 73856093u) ^
                     (static_cast<uint32_t>(c.y) * 19349663u) ^
                     (static_cast<uint32_t>(c.z) * 83492791u);
  return h & mask_;
}

}  // namespace photon

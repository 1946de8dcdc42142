// Vertex merging's range search (Georgiev et al. 2012 sec. 5.2; SmallVCM's hash grid): light
// vertices hashed into cells of twice the merging radius, so the disc of radius r around any
// point lies in the 2 x 2 x 2 cells nearest it. Built by a counting sort in vertex order, so a
// query visits vertices in a fixed order whatever the thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "photon/integrators/vcm/vcm_common.h"

namespace photon {

class VcmGrid {
 public:
  VcmGrid() = default;
  VcmGrid(const std::vector<VcmLightVertex>& vertices, float radius);

  // Calls f(vertex) for every vertex within the radius of p, in a fixed order.
  template <typename F>
  void for_each_within(const Vec3& p, F&& f) const {
    if (cells_.empty() || !vertices_) return;
    const Vec3 g = (p - lo_) * inv_cell_;
    const int px = static_cast<int>(std::floor(g.x)), py = static_cast<int>(std::floor(g.y)),
              pz = static_cast<int>(std::floor(g.z));
    // The neighbour on the side of p's half of its cell, per axis.
    const int nx = g.x - px < 0.5f ? px - 1 : px, ny = g.y - py < 0.5f ? py - 1 : py,
              nz = g.z - pz < 0.5f ? pz - 1 : pz;
    uint32_t buckets[8];
    int count = 0;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const uint32_t b = bucket(nx + dx, ny + dy, nz + dz);
          bool seen = false;
          for (int k = 0; k < count; ++k) seen = seen || buckets[k] == b;
          if (!seen) buckets[count++] = b;
        }
    // Buckets in increasing order, so the summation order does not depend on p's position in
    // its cell beyond which buckets it reads.
    for (int i = 1; i < count; ++i)  // insertion sort of at most 8
      for (int k = i; k > 0 && buckets[k - 1] > buckets[k]; --k)
        std::swap(buckets[k - 1], buckets[k]);
    for (int k = 0; k < count; ++k) {
      const uint32_t b = buckets[k];
      for (uint32_t i = cells_[b]; i < cells_[b + 1]; ++i) {
        const VcmLightVertex& v = (*vertices_)[indices_[i]];
        if (length_squared(v.p - p) <= radius2_) f(v);
      }
    }
  }

 private:
  uint32_t bucket(int x, int y, int z) const {
    const uint32_t h = (static_cast<uint32_t>(x) * 73856093u) ^
                       (static_cast<uint32_t>(y) * 19349663u) ^
                       (static_cast<uint32_t>(z) * 83492791u);
    return h & mask_;
  }

  const std::vector<VcmLightVertex>* vertices_ = nullptr;
  std::vector<uint32_t> cells_;    // bucket b holds indices_[cells_[b] .. cells_[b + 1])
  std::vector<uint32_t> indices_;  // vertex indices sorted by bucket, in vertex order within
  Vec3 lo_{0.0f};
  float inv_cell_ = 1.0f, radius2_ = 0.0f;
  uint32_t mask_ = 0;
};

}  // namespace photon

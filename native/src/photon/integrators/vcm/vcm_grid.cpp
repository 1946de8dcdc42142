#include "photon/integrators/vcm/vcm_grid.h"

#include <cmath>

namespace photon {

VcmGrid::VcmGrid(const std::vector<VcmLightVertex>& vertices, float radius)
    : vertices_(&vertices), radius2_(radius * radius) {
  if (vertices.empty() || !(radius > 0.0f)) return;
  lo_ = vertices[0].p;
  for (const VcmLightVertex& v : vertices) lo_ = min(lo_, v.p);
  inv_cell_ = 1.0f / (2.0f * radius);
  uint32_t size = 1;
  while (size < vertices.size() && size < (1u << 30)) size <<= 1;
  mask_ = size - 1;
  std::vector<uint32_t> bucket_of(vertices.size());
  cells_.assign(static_cast<size_t>(size) + 1, 0);
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec3 g = (vertices[i].p - lo_) * inv_cell_;
    bucket_of[i] = bucket(static_cast<int>(std::floor(g.x)), static_cast<int>(std::floor(g.y)),
                          static_cast<int>(std::floor(g.z)));
    ++cells_[bucket_of[i] + 1];
  }
  for (size_t b = 0; b < size; ++b) cells_[b + 1] += cells_[b];
  indices_.resize(vertices.size());
  std::vector<uint32_t> next(cells_.begin(), cells_.end() - 1);
  for (size_t i = 0; i < vertices.size(); ++i)
    indices_[next[bucket_of[i]]++] = static_cast<uint32_t>(i);
}

}  // namespace photon

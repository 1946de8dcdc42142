#include "photon/integrators/sppm/photon_kdtree.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>

namespace photon {
namespace {

// Below this many photons a subtree is built on the calling thread.
constexpr size_t kParallelRange = 1 << 14;

}  // namespace

PhotonKdTree::PhotonKdTree(std::vector<SppmPhoton> photons)
    : photons_(std::move(photons)), axes_(photons_.size(), 0) {
  build(0, photons_.size());
}

void PhotonKdTree::build(size_t lo, size_t hi) {
  if (hi - lo <= kLeafSize) return;
  // Split the range's bounding box across its longest side at the median (Jensen 2001,
  // sec. 6.3). nth_element is deterministic for a given input, so is the tree.
  Vec3 bmin(INFINITY), bmax(-INFINITY);
  for (size_t i = lo; i < hi; ++i) {
    bmin = min(bmin, photons_[i].p);
    bmax = max(bmax, photons_[i].p);
  }
  const Vec3 extent = bmax - bmin;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const size_t mid = lo + (hi - lo) / 2;
  std::nth_element(
      photons_.begin() + lo, photons_.begin() + mid, photons_.begin() + hi,
      [axis](const SppmPhoton& a, const SppmPhoton& b) { return a.p[axis] < b.p[axis]; });
  axes_[mid] = static_cast<uint8_t>(axis);
  if (hi - lo >= kParallelRange)
    tbb::parallel_invoke([&] { build(lo, mid); }, [&] { build(mid + 1, hi); });
  else {
    build(lo, mid);
    build(mid + 1, hi);
  }
}

}  // namespace photon

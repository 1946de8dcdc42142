// A bounding volume hierarchy over emitters, traversed stochastically to pick one emitter per
// shading point with a probability that follows each cluster's estimated contribution there
// (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
// Splitting", sec. 4 and 5.1). The probability of the emitter picked is the product of the
// choices down the tree, and pmf() recomputes it for any emitter, which multiple importance
// sampling needs when a BSDF-sampled ray hits a light.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "photon/base/math.h"
#include "photon/lights/light_bounds.h"

namespace photon {

class LightTree {
 public:
  LightTree() = default;
  // One leaf per entry of `bounds`. Entries without power (zero, negative, NaN), with a
  // non-finite box or marked infinite are left out: sample() never returns them and their pmf
  // is 0. `hittable[i]` (optional) marks entries a ray can hit (for_each_hit visits only them).
  explicit LightTree(const std::vector<LightBounds>& bounds,
                     const std::vector<bool>& hittable = {});

  bool empty() const { return nodes_.empty(); }
  size_t size() const { return leaf_count_; }  // emitters in the tree
  const LightBounds& root_bounds() const { return nodes_[0].bounds; }

  // Picks an emitter for the shading point `p` with u in [0, 1). False if no emitter can light
  // p (every cluster's importance is 0 there).
  bool sample(const Vec3& p, float u, uint32_t* index, float* pmf) const;
  // Probability that sample() at `p` returns `index`.
  float pmf(const Vec3& p, uint32_t index) const;

  // Calls f(index) for every hittable entry whose box the ray crosses between tmin and tmax.
  template <class F>
  void for_each_hit(const Ray& ray, F&& f) const;

  // Conty Estevez & Kulla 2018, eq. 3: the importance of a cluster for point p,
  //   I = Phi * cos(theta') / d^2 if theta' < theta_e, else 0,  theta' = max(0, theta - theta_o -
  //   theta_u),
  // with theta the angle between the cluster's axis and the direction from its centre to p and
  // theta_u the half angle its box subtends from p (so the bound holds for every emitter in it).
  // d^2 is kept at least the square of half the box's diagonal, so clusters next to or around p
  // do not take every sample.
  static float importance(const Vec3& p, const LightBounds& b);

 private:
  struct Node {
    LightBounds bounds;
    uint32_t child = 0;  // inner: index of the first child (the second follows it); leaf: entry
    bool leaf = false;
    bool hittable = false;  // some entry below can be hit by a ray
  };
  void build(std::vector<uint32_t>& items, size_t begin, size_t end,
             const std::vector<LightBounds>& bounds, const std::vector<bool>& hittable,
             uint32_t node, uint64_t path, int depth);
  std::vector<Node> nodes_;
  // Per entry: the left (0) / right (1) choices from the root to its leaf, and their number
  // (depth -1 for entries left out).
  std::vector<uint64_t> path_;
  std::vector<int8_t> depth_;
  size_t leaf_count_ = 0;
};

namespace light_tree_detail {
inline bool ray_box(const Ray& ray, const Vec3& inv, const Vec3& lo, const Vec3& hi) {
  float t0 = ray.tmin, t1 = ray.tmax;
  const float o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const float d[3] = {inv.x, inv.y, inv.z};
  const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
  for (int a = 0; a < 3; ++a) {
    float tn = (l[a] - o[a]) * d[a], tf = (h[a] - o[a]) * d[a];
    if (tn > tf) std::swap(tn, tf);
    // A zero direction component gives 0 * inf = NaN when the origin is on a slab plane:
    // treat it as inside that slab.
    if (!(tn == tn)) tn = -INFINITY;
    if (!(tf == tf)) tf = INFINITY;
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf * 1.0000004f);
    if (t0 > t1) return false;
  }
  return true;
}
}  // namespace light_tree_detail

template <class F>
void LightTree::for_each_hit(const Ray& ray, F&& f) const {
  if (nodes_.empty() || !nodes_[0].hittable) return;
  const Vec3 inv(1.0f / ray.direction.x, 1.0f / ray.direction.y, 1.0f / ray.direction.z);
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!n.hittable || !light_tree_detail::ray_box(ray, inv, n.bounds.lo, n.bounds.hi)) continue;
    if (n.leaf) {
      f(n.child);
    } else {
      stack[top++] = n.child;
      stack[top++] = n.child + 1;
    }
  }
}

}  // namespace photon

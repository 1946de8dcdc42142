// A balanced kd-tree stored implicitly in an array of points (Jensen 2001, "Realistic Image
// Synthesis Using Photon Mapping", sec. 6.3; the shape of Nori's PointKDTree<Node>): the median
// of every range is that range's node, split across the longest side of the range's bounds, so
// the tree costs no memory beyond the points and their split axes. Both photon stores use it:
// the photon maps (k nearest photons) and SPPM's per-iteration photons (every photon within a
// radius).
//
// A node type says where it is and where its split axis lives, through PointKdNode<Node>:
//   static float coordinate(const Node&, int axis);
//   static Vec3 position(const Node&);
//   static constexpr bool kAxisInNode;  // the axis is packed into the node (set_axis, axis),
//                                       // else the tree keeps one byte per node beside them
//   static int axis(const Node&);  static void set_axis(Node&, int);  (when kAxisInNode)
// Ranges of at most LeafSize nodes are leaves, scanned rather than split (axis 0).
//
// Determinism: the tree is a function of the nodes and their order (nth_element is
// deterministic; big halves build in parallel on disjoint ranges), and a query visits nodes in
// an order fixed by the tree and the query alone, so sums over a query's nodes are the same
// bits whatever the threads do.
#pragma once

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "photon/base/cancel_poll.h"
#include "photon/base/math.h"

namespace photon {

template <class Node>
struct PointKdNode;

struct KdNeighbor {
  uint32_t index;
  float distance_squared;
};

template <class Node, size_t LeafSize = 1>
class PointKdTree {
  using Traits = PointKdNode<Node>;

 public:
  PointKdTree() = default;
  // Takes the nodes and balances the tree. When `cancel` is set during the build, Cancelled is
  // thrown (polled every few thousand steps).
  explicit PointKdTree(std::vector<Node> nodes, const std::atomic<bool>* cancel = nullptr)
      : nodes_(std::move(nodes)) {
    if constexpr (!Traits::kAxisInNode) axes_.assign(nodes_.size(), 0);
    build(0, nodes_.size(), 0, cancel);
  }
  // Nodes already in a tree's balanced order with their split axes (a saved tree's nodes()).
  static PointKdTree from_balanced(std::vector<Node> nodes) {
    static_assert(Traits::kAxisInNode, "the split axes travel with the nodes");
    PointKdTree tree;
    tree.nodes_ = std::move(nodes);
    return tree;
  }

  size_t size() const { return nodes_.size(); }
  bool empty() const { return nodes_.empty(); }
  const Node& operator[](size_t i) const { return nodes_[i]; }
  // The nodes in balanced order (the implicit tree).
  const std::vector<Node>& nodes() const { return nodes_; }
  size_t memory_bytes() const { return nodes_.capacity() * sizeof(Node) + axes_.capacity(); }

  // Calls f(node) for every node within `radius` of `p`, in an order fixed by the tree and p.
  template <class F>
  void for_each_within(const Vec3& p, float radius, F&& f) const {
    if (nodes_.empty() || !(radius > 0.0f)) return;
    visit(0, nodes_.size(), p, radius * radius, radius, f);
  }

  // The `k` nearest nodes to `p` within `max_radius` that `accept` takes, written to `out`
  // (cleared first) as a max-heap on distance: out->front() is the farthest.
  template <class Accept>
  void k_nearest(const Vec3& p, size_t k, float max_radius, Accept&& accept,
                 std::vector<KdNeighbor>* out) const {
    k_nearest(
        p, k, max_radius, accept, [](const Node&, float) { return true; }, out);
  }
  // As above, with a second test `accept_near(node, squared distance)` asked only of nodes
  // that `accept` takes and that are nearer than the k found so far (for tests that cost more).
  template <class Accept, class AcceptNear>
  void k_nearest(const Vec3& p, size_t k, float max_radius, Accept&& accept,
                 AcceptNear&& accept_near, std::vector<KdNeighbor>* out) const;

 private:
  int axis_of(size_t i) const {
    if constexpr (Traits::kAxisInNode)
      return Traits::axis(nodes_[i]);
    else
      return axes_[i];
  }
  void set_axis(size_t i, int axis) {
    if constexpr (Traits::kAxisInNode)
      Traits::set_axis(nodes_[i], axis);
    else
      axes_[i] = static_cast<uint8_t>(axis);
  }
  void build(size_t lo, size_t hi, int depth, const std::atomic<bool>* cancel);
  template <class F>
  void visit(size_t lo, size_t hi, const Vec3& p, float r2, float r, F& f) const;

  std::vector<Node> nodes_;
  std::vector<uint8_t> axes_;  // split axes, unless the nodes hold them
};

// Balances [lo, hi): the median along the widest axis of the range's bounds becomes the node at
// (lo + hi) / 2, smaller coordinates to its left.
template <class Node, size_t LeafSize>
void PointKdTree<Node, LeafSize>::build(size_t lo, size_t hi, int depth,
                                        const std::atomic<bool>* cancel) {
  if (hi - lo <= LeafSize) {
    for (size_t i = lo; i < hi; ++i) set_axis(i, 0);
    return;
  }
  CancelPoll poll(cancel);
  float bmin[3] = {INFINITY, INFINITY, INFINITY}, bmax[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = lo; i < hi; ++i) {
    poll();
    for (int a = 0; a < 3; ++a) {
      bmin[a] = std::min(bmin[a], Traits::coordinate(nodes_[i], a));
      bmax[a] = std::max(bmax[a], Traits::coordinate(nodes_[i], a));
    }
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (bmax[a] - bmin[a] > bmax[axis] - bmin[axis]) axis = a;
  const size_t mid = (lo + hi) / 2;
  std::nth_element(nodes_.begin() + lo, nodes_.begin() + mid, nodes_.begin() + hi,
                   [axis, &poll](const Node& a, const Node& b) {
                     poll();
                     return Traits::coordinate(a, axis) < Traits::coordinate(b, axis);
                   });
  set_axis(mid, axis);
  // Cancelled thrown in either half reaches the constructor (TBB rethrows it here).
  if (hi - lo > 65536 && depth < 12) {
    tbb::parallel_invoke([&] { build(lo, mid, depth + 1, cancel); },
                         [&] { build(mid + 1, hi, depth + 1, cancel); });
  } else {
    build(lo, mid, depth + 1, cancel);
    build(mid + 1, hi, depth + 1, cancel);
  }
}

template <class Node, size_t LeafSize>
template <class F>
void PointKdTree<Node, LeafSize>::visit(size_t lo, size_t hi, const Vec3& p, float r2, float r,
                                        F& f) const {
  while (hi - lo > LeafSize) {
    const size_t mid = (lo + hi) / 2;
    const Node& node = nodes_[mid];
    const int axis = axis_of(mid);
    const float d = p[axis] - Traits::coordinate(node, axis);
    // [lo, mid) lies at or below the split, (mid, hi) at or above it.
    if (d <= r) visit(lo, mid, p, r2, r, f);
    const Vec3 v = Traits::position(node) - p;
    if (dot(v, v) <= r2) f(node);
    if (d < -r) return;
    lo = mid + 1;
  }
  for (size_t i = lo; i < hi; ++i) {
    const Vec3 v = Traits::position(nodes_[i]) - p;
    if (dot(v, v) <= r2) f(nodes_[i]);
  }
}

template <class Node, size_t LeafSize>
template <class Accept, class AcceptNear>
void PointKdTree<Node, LeafSize>::k_nearest(const Vec3& p, size_t k, float max_radius,
                                            Accept&& accept, AcceptNear&& accept_near,
                                            std::vector<KdNeighbor>* out) const {
  static_assert(LeafSize == 1, "k_nearest descends to single nodes");
  out->clear();
  if (nodes_.empty() || k == 0) return;
  float max_d2 = max_radius * max_radius;
  const float q[3] = {p.x, p.y, p.z};
  auto farther = [](const KdNeighbor& a, const KdNeighbor& b) {
    return a.distance_squared < b.distance_squared;
  };
  // Explicit stack of far sides with their splitting plane's squared distance; at most one
  // entry per tree level is pending, and the tree is under 40 levels deep.
  struct Range {
    uint32_t lo, hi;
    float plane_d2;
  };
  Range stack[64];
  int top = 0;
  stack[top++] = {0, static_cast<uint32_t>(nodes_.size()), 0.0f};
  while (top > 0) {
    Range r = stack[--top];
    if (r.plane_d2 >= max_d2) continue;  // the radius shrank since it was queued
    while (r.hi > r.lo) {
      const uint32_t mid = (r.lo + r.hi) / 2;
      const Node& node = nodes_[mid];
      const int axis = axis_of(mid);
      const float delta = q[axis] - Traits::coordinate(node, axis);
      // Visit the near side now, queue the far side if the splitting plane is within reach.
      const float d2_plane = delta * delta;
      const Range near_side = delta < 0.0f ? Range{r.lo, mid, 0.0f} : Range{mid + 1, r.hi, 0.0f};
      const Range far_side =
          delta < 0.0f ? Range{mid + 1, r.hi, d2_plane} : Range{r.lo, mid, d2_plane};
      if (d2_plane < max_d2 && far_side.hi > far_side.lo) stack[top++] = far_side;
      if (accept(node)) {
        const float dx = Traits::coordinate(node, 0) - q[0],
                    dy = Traits::coordinate(node, 1) - q[1],
                    dz = Traits::coordinate(node, 2) - q[2];
        const float d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < max_d2 && accept_near(node, d2)) {
          if (out->size() < k) {
            out->push_back({mid, d2});
            std::push_heap(out->begin(), out->end(), farther);
            if (out->size() == k) max_d2 = out->front().distance_squared;
          } else {
            std::pop_heap(out->begin(), out->end(), farther);
            out->back() = {mid, d2};
            std::push_heap(out->begin(), out->end(), farther);
            max_d2 = out->front().distance_squared;
          }
        }
      }
      r = near_side;
    }
  }
}

}  // namespace photon

#include "photon/integrators/photon_map/irradiance_cache.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

constexpr uint32_t kLeafSize = 4;
// Ward's d_i test tolerates records this far (in units of R_i) in front of the point, so
// curved surfaces and float round-off do not reject a record lying on the surface itself.
constexpr float kInFrontTolerance = 0.02f;

}  // namespace

float ward_error(const IrradianceRecord& record, const Vec3& p, const Vec3& n) {
  const float c = dot(n, record.n);
  if (!(c > 0.0f)) return INFINITY;
  return length(p - record.p) / record.radius + std::sqrt(std::max(0.0f, 1.0f - c));
}

bool record_in_front(const IrradianceRecord& record, const Vec3& p, const Vec3& n) {
  // Ward 1988: d_i = (x - x_i) . (n + n_i) / 2 < 0 puts the record in front of x.
  return dot(p - record.p, (n + record.n) * 0.5f) < -kInFrontTolerance * record.radius;
}

IrradianceCache::IrradianceCache(std::vector<IrradianceRecord> records, float accuracy)
    : accuracy_(accuracy > 0.0f && std::isfinite(accuracy) ? accuracy : 0.25f) {
  for (IrradianceRecord& r : records)
    if (is_finite(r.p) && is_finite(r.n) && is_finite(r.value) && r.radius > 0.0f &&
        std::isfinite(r.radius))
      records_.push_back(r);
  order_.resize(records_.size());
  for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  if (!records_.empty()) {
    nodes_.reserve(2 * records_.size() / kLeafSize + 1);
    build(0, static_cast<uint32_t>(order_.size()));
  }
}

size_t IrradianceCache::memory_bytes() const {
  return records_.capacity() * sizeof(IrradianceRecord) + order_.capacity() * sizeof(uint32_t) +
         nodes_.capacity() * sizeof(Node);
}

uint32_t IrradianceCache::build(uint32_t begin, uint32_t end) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lo(INFINITY), hi(-INFINITY), clo(INFINITY), chi(-INFINITY);
  for (uint32_t i = begin; i < end; ++i) {
    const IrradianceRecord& r = records_[order_[i]];
    const Vec3 reach(accuracy_ * r.radius);
    lo = min(lo, r.p - reach);
    hi = max(hi, r.p + reach);
    clo = min(clo, r.p);
    chi = max(chi, r.p);
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  // Median split on the widest axis of the centres; ties broken by index, so the tree depends
  // only on the records.
  const Vec3 extent = chi - clo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](uint32_t a, uint32_t b) {
                     const float ka = records_[a].p[axis], kb = records_[b].p[axis];
                     return ka < kb || (ka == kb && a < b);
                   });
  build(begin, mid);
  const uint32_t right = build(mid, end);
  nodes_[index].first = right;
  return index;
}

template <typename Visit>
void IrradianceCache::for_each_candidate(const Vec3& p, Visit&& visit) const {
  if (nodes_.empty()) return;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (p.x < node.lo.x || p.y < node.lo.y || p.z < node.lo.z || p.x > node.hi.x ||
        p.y > node.hi.y || p.z > node.hi.z)
      continue;
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i)
        if (visit(records_[order_[i]])) return;
    } else {
      const uint32_t self = static_cast<uint32_t>(&node - nodes_.data());
      // Depth is about log2(records / 4) < 64 for any record count that fits in memory.
      stack[top++] = node.first;
      stack[top++] = self + 1;
    }
  }
}

bool IrradianceCache::lookup(const Vec3& p, const Vec3& n, Vec3* value) const {
  const float inv_a = 1.0f / accuracy_;
  Vec3 sum(0.0f);
  float weight_sum = 0.0f;
  for_each_candidate(p, [&](const IrradianceRecord& r) {
    const float eps = ward_error(r, p, n);
    if (!(eps < accuracy_) || record_in_front(r, p, n)) return false;
    // Ward's w = 1/eps, shifted so it vanishes at eps = a (see the header).
    const float w = 1.0f / std::max(eps, 1e-4f * accuracy_) - inv_a;
    sum += r.value * w;
    weight_sum += w;
    return false;
  });
  if (!(weight_sum > 0.0f)) return false;
  *value = sum / weight_sum;
  return true;
}

bool IrradianceCache::covers(const Vec3& p, const Vec3& n, float max_error) const {
  bool found = false;
  for_each_candidate(p, [&](const IrradianceRecord& r) {
    found = ward_error(r, p, n) < max_error && !record_in_front(r, p, n);
    return found;
  });
  return found;
}

}  // namespace photon

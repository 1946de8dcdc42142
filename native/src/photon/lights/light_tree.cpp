#include "photon/lights/light_tree.h"

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

float safe_acos(float c) {
  return std::acos(std::clamp(c, -1.0f, 1.0f));
}

// Rotates unit `v` by `angle` about unit `w` perpendicular to it (Rodrigues' formula).
Vec3 rotate_perpendicular(const Vec3& v, const Vec3& w, float angle) {
  return v * std::cos(angle) + cross(w, v) * std::sin(angle);
}

bool finite_bounds(const LightBounds& b) {
  return is_finite(b.lo) && is_finite(b.hi) && is_finite(b.axis) && std::isfinite(b.cos_theta_o) &&
         std::isfinite(b.cos_theta_e) && std::isfinite(b.power) && !b.empty();
}

}  // namespace

LightBounds merge(const LightBounds& a, const LightBounds& b) {
  if (!(a.power > 0.0f) || a.empty()) return b;
  if (!(b.power > 0.0f) || b.empty()) return a;
  LightBounds m;
  m.lo = min(a.lo, b.lo);
  m.hi = max(a.hi, b.hi);
  m.power = a.power + b.power;
  m.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  m.infinite = a.infinite || b.infinite;
  // Conty Estevez & Kulla 2018, Algorithm 1: the cone bounding two normal cones.
  const float theta_a = safe_acos(a.cos_theta_o), theta_b = safe_acos(b.cos_theta_o);
  const float theta_d = safe_acos(dot(a.axis, b.axis));
  if (std::min(theta_d + theta_b, kPi) <= theta_a) {
    m.axis = a.axis;
    m.cos_theta_o = a.cos_theta_o;
    return m;
  }
  if (std::min(theta_d + theta_a, kPi) <= theta_b) {
    m.axis = b.axis;
    m.cos_theta_o = b.cos_theta_o;
    return m;
  }
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
  const Vec3 w = cross(a.axis, b.axis);
  if (theta_o >= kPi || !(length_squared(w) > 1e-12f)) {
    m.axis = a.axis;
    m.cos_theta_o = -1.0f;
    return m;
  }
  m.axis = normalize(rotate_perpendicular(a.axis, normalize(w), theta_o - theta_a));
  m.cos_theta_o = std::cos(theta_o);
  return m;
}

float LightTree::importance(const Vec3& p, const LightBounds& b) {
  const Vec3 center = (b.lo + b.hi) * 0.5f;
  const Vec3 half_diagonal = (b.hi - b.lo) * 0.5f;
  const float r2 = length_squared(half_diagonal);
  const Vec3 to_p = p - center;
  const float dist2 = length_squared(to_p);
  const float d2 = std::max(dist2, r2);
  if (!(d2 > 0.0f)) return b.power;  // a single point light at p itself
  const bool inside = p.x >= b.lo.x && p.y >= b.lo.y && p.z >= b.lo.z && p.x <= b.hi.x &&
                      p.y <= b.hi.y && p.z <= b.hi.z;
  if (inside || dist2 <= r2) return b.power / d2;  // every direction is possible
  // theta: axis to the direction from the centre to p; theta_u: the box's half angle from p
  // (the bounding sphere of the box, conservative). The angle differences are taken on cosines
  // and sines, clamped at 0 (as in pbrt-v4's CompactLightBounds::Importance), without acos.
  const float cos_theta = std::clamp(dot(b.axis, to_p) / std::sqrt(dist2), -1.0f, 1.0f);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float sin2_u = std::min(1.0f, r2 / dist2);
  const float sin_u = std::sqrt(sin2_u), cos_u = std::sqrt(1.0f - sin2_u);
  const float cos_o = std::clamp(b.cos_theta_o, -1.0f, 1.0f);
  const float sin_o = std::sqrt(std::max(0.0f, 1.0f - cos_o * cos_o));
  // cos and sin of max(0, a - b) from those of a and b.
  auto cos_sub = [](float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
  };
  auto sin_sub = [](float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
  };
  const float cos_x = cos_sub(sin_theta, cos_theta, sin_o, cos_o);
  const float sin_x = sin_sub(sin_theta, cos_theta, sin_o, cos_o);
  const float cos_p = cos_sub(sin_x, cos_x, sin_u, cos_u);  // theta' = max(0, theta_x - theta_u)
  if (cos_p <= b.cos_theta_e) return 0.0f;
  return b.power * cos_p / d2;
}

LightTree::LightTree(const std::vector<LightBounds>& bounds, const std::vector<bool>& hittable) {
  path_.assign(bounds.size(), 0);
  depth_.assign(bounds.size(), -1);
  std::vector<uint32_t> items;
  for (uint32_t i = 0; i < bounds.size(); ++i)
    if (!bounds[i].infinite && bounds[i].power > 0.0f && finite_bounds(bounds[i]))
      items.push_back(i);
  leaf_count_ = items.size();
  if (items.empty()) return;
  nodes_.reserve(2 * items.size());
  nodes_.emplace_back();
  build(items, 0, items.size(), bounds, hittable, 0, 0, 0);
}

// Builds items[begin, end) into nodes_[node] (already allocated).
void LightTree::build(std::vector<uint32_t>& items, size_t begin, size_t end,
                      const std::vector<LightBounds>& bounds, const std::vector<bool>& hittable,
                      uint32_t node, uint64_t path, int depth) {
  if (end - begin == 1) {
    const uint32_t i = items[begin];
    Node& n = nodes_[node];
    n.bounds = bounds[i];
    n.leaf = true;
    n.child = i;
    n.hittable = i < hittable.size() && hittable[i];
    path_[i] = path;
    depth_[i] = static_cast<int8_t>(depth);
    return;
  }
  // Split at the median centroid along the widest axis of the centroids (a balanced tree:
  // depth log2(n), so the paths fit 64 bits).
  Vec3 clo(INFINITY), chi(-INFINITY);
  for (size_t k = begin; k < end; ++k) {
    const Vec3 c = (bounds[items[k]].lo + bounds[items[k]].hi) * 0.5f;
    clo = min(clo, c);
    chi = max(chi, c);
  }
  const Vec3 extent = chi - clo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  auto key = [&](uint32_t i) {
    const Vec3 c = bounds[i].lo + bounds[i].hi;
    return axis == 0 ? c.x : axis == 1 ? c.y : c.z;
  };
  // Ties broken by index, so the tree is the same on every platform.
  std::sort(items.begin() + begin, items.begin() + end, [&](uint32_t a, uint32_t b) {
    const float ka = key(a), kb = key(b);
    return ka < kb || (ka == kb && a < b);
  });
  const size_t mid = begin + (end - begin) / 2;
  const uint32_t first = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[node].child = first;
  build(items, begin, mid, bounds, hittable, first, path, depth + 1);
  build(items, mid, end, bounds, hittable, first + 1, path | (1ull << depth), depth + 1);
  Node& n = nodes_[node];
  n.bounds = merge(nodes_[first].bounds, nodes_[first + 1].bounds);
  n.hittable = nodes_[first].hittable || nodes_[first + 1].hittable;
}

bool LightTree::sample(const Vec3& p, float u, uint32_t* index, float* pmf) const {
  if (nodes_.empty()) return false;
  float prob = 1.0f;
  uint32_t node = 0;
  while (!nodes_[node].leaf) {
    const uint32_t c = nodes_[node].child;
    const float il = importance(p, nodes_[c].bounds), ir = importance(p, nodes_[c + 1].bounds);
    if (!(il + ir > 0.0f)) return false;
    const float pl = il / (il + ir);
    if (u < pl) {
      u = std::min(u / pl, 0.99999994f);
      prob *= pl;
      node = c;
    } else {
      u = std::min((u - pl) / (1.0f - pl), 0.99999994f);
      prob *= 1.0f - pl;
      node = c + 1;
    }
  }
  if (!(prob > 0.0f)) return false;
  *index = nodes_[node].child;
  *pmf = prob;
  return true;
}

float LightTree::pmf(const Vec3& p, uint32_t index) const {
  if (index >= depth_.size() || depth_[index] < 0) return 0.0f;
  float prob = 1.0f;
  uint32_t node = 0;
  for (int level = 0; level < depth_[index]; ++level) {
    const uint32_t c = nodes_[node].child;
    const float il = importance(p, nodes_[c].bounds), ir = importance(p, nodes_[c + 1].bounds);
    if (!(il + ir > 0.0f)) return 0.0f;
    const float pl = il / (il + ir);
    if ((path_[index] >> level) & 1) {
      prob *= 1.0f - pl;
      node = c + 1;
    } else {
      prob *= pl;
      node = c;
    }
  }
  return prob;
}

}  // namespace photon

#include "photon/radiosity_mesh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <unordered_map>

#include "photon/rng.h"

namespace photon {
namespace {

struct TriangleInput {
  Vec3 world[3];
  Vec3 centroid;
  float longest = 0.0f;  // world-space longest edge
  float area = 0.0f;
  uint32_t instance = 0;  // Embree instance id
  uint32_t slot = 0;      // material slot
  uint8_t axis = 0;       // dominant axis of the normal: 2 * axis + (component < 0)
  bool meshed = false;
};

uint32_t subdivisions(float longest, float patch_size, uint32_t max_subdivisions) {
  if (!(patch_size > 0.0f)) return 1;
  const double n = std::ceil(static_cast<double>(longest) / patch_size);
  return static_cast<uint32_t>(std::clamp(n, 1.0, static_cast<double>(max_subdivisions)));
}

struct Sizing {
  uint32_t max_subdivisions = 1;
  float cluster_fraction = 0.5f;
};

bool is_clustered(const TriangleInput& t, float patch_size, const Sizing& sizing) {
  return patch_size > 0.0f && t.longest < sizing.cluster_fraction * patch_size;
}

// A cluster: instance, material slot, normal axis and the world voxel (edge = patch size) that
// holds the triangle's centroid. Voxel coordinates are clamped to 21 bits each.
struct ClusterKey {
  uint64_t a = 0, b = 0;
  bool operator==(const ClusterKey& o) const { return a == o.a && b == o.b; }
  bool operator<(const ClusterKey& o) const { return a != o.a ? a < o.a : b < o.b; }
};
struct ClusterKeyHash {
  size_t operator()(const ClusterKey& k) const {
    return static_cast<size_t>(hash_combine(k.a, k.b));
  }
};
uint64_t voxel_bits(float x, float size) {
  constexpr double kHalf = 1 << 20;
  const double v = std::clamp(std::floor(static_cast<double>(x) / size), -kHalf, kHalf - 1);
  return static_cast<uint64_t>(static_cast<int64_t>(v) + static_cast<int64_t>(kHalf));
}
ClusterKey cluster_key(const TriangleInput& t, float size) {
  return {static_cast<uint64_t>(t.instance) << 32 |
              static_cast<uint64_t>(t.slot & 0x1fffffffu) << 3 | t.axis,
          voxel_bits(t.centroid.x, size) << 42 | voxel_bits(t.centroid.y, size) << 21 |
              voxel_bits(t.centroid.z, size)};
}

// Patches for a patch size: n^2 per subdivided triangle plus one per occupied cluster. Run
// about a dozen times on every triangle by the size search, so in parallel; clusters are
// counted by a 63-bit hash of their key (a collision would only undercount by one).
size_t patch_count_for(const std::vector<TriangleInput>& tris, float patch_size,
                       const Sizing& sizing) {
  constexpr uint64_t kNone = UINT64_MAX;
  std::vector<uint64_t> keys(tris.size());
  const size_t subdivided = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, tris.size(), 4096), size_t(0),
      [&](const tbb::blocked_range<size_t>& range, size_t count) {
        for (size_t i = range.begin(); i < range.end(); ++i) {
          const TriangleInput& t = tris[i];
          keys[i] = kNone;
          if (!t.meshed) continue;
          if (is_clustered(t, patch_size, sizing)) {
            const ClusterKey k = cluster_key(t, patch_size);
            keys[i] = hash_combine(k.a, k.b) >> 1;
          } else {
            const size_t n = subdivisions(t.longest, patch_size, sizing.max_subdivisions);
            count += n * n;
          }
        }
        return count;
      },
      std::plus<size_t>());
  tbb::parallel_sort(keys.begin(), keys.end());
  const auto end = std::lower_bound(keys.begin(), keys.end(), kNone);
  return subdivided + static_cast<size_t>(std::unique(keys.begin(), end) - keys.begin());
}

// The smallest patch size (within 1%) whose patch count does not exceed `target`, by bisection
// on log(size): the count falls (nearly) monotonically as the size grows. Sizes up to the
// longest edge are searched first (the search of one patch per small triangle, unchanged for
// meshes that cluster nothing); dense meshes need sizes up to the scene's extent.
float size_for_count(const std::vector<TriangleInput>& tris, size_t target, float largest,
                     float extent, const Sizing& sizing) {
  const size_t at_largest = patch_count_for(tris, largest, sizing);
  if (at_largest == target) return largest;
  double lo = std::log(static_cast<double>(largest) * 1e-6),
         hi = std::log(static_cast<double>(largest));
  if (at_largest > target) {
    if (!(extent > largest) || patch_count_for(tris, extent, sizing) >= target) return extent;
    lo = hi;
    hi = std::log(static_cast<double>(extent));
  }
  for (int k = 0; k < 40 && hi - lo > 0.01; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (patch_count_for(tris, static_cast<float>(std::exp(mid)), sizing) > target)
      lo = mid;
    else
      hi = mid;
  }
  return static_cast<float>(std::exp(hi));
}

// Welding key: the exact bits of an object-space position. Points shared by two triangles are
// computed from the same endpoints in the same order (see lattice_position), so they agree bit
// for bit.
struct PositionKey {
  uint32_t bits[3];
  bool operator==(const PositionKey& o) const {
    return std::memcmp(bits, o.bits, sizeof bits) == 0;
  }
};
struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    return static_cast<size_t>(hash_combine(hash_combine(k.bits[0], k.bits[1]), k.bits[2]));
  }
};
PositionKey key_of(const Vec3& p) {
  PositionKey k;
  std::memcpy(&k.bits[0], &p.x, 4);
  std::memcpy(&k.bits[1], &p.y, 4);
  std::memcpy(&k.bits[2], &p.z, 4);
  return k;
}

bool lexicographic_less(const Vec3& a, const Vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// Object-space position of lattice point (a, b) of a triangle subdivided n times. Edge points
// interpolate between the edge's endpoints taken in lexicographic order, so the two triangles
// sharing an edge compute the same bits (also when their n differ but k/n agree, e.g. 1/2, 2/4).
Vec3 lattice_position(const Vec3 p[3], uint32_t n, uint32_t a, uint32_t b, bool* interior) {
  *interior = false;
  if (a == 0 && b == 0) return p[0];
  if (a == n) return p[1];
  if (b == n) return p[2];
  Vec3 from, to;
  uint32_t k;
  if (b == 0) {
    from = p[0], to = p[1], k = a;
  } else if (a == 0) {
    from = p[0], to = p[2], k = b;
  } else if (a + b == n) {
    from = p[1], to = p[2], k = b;
  } else {
    *interior = true;
    const float fa = static_cast<float>(a) / n, fb = static_cast<float>(b) / n;
    return p[0] + (p[1] - p[0]) * fa + (p[2] - p[0]) * fb;
  }
  if (lexicographic_less(to, from)) {
    std::swap(from, to);
    k = n - k;
  }
  return from + (to - from) * (static_cast<float>(k) / static_cast<float>(n));
}

struct WeldCluster {
  uint32_t vertex;
  Vec3 normal;     // the normal compared (shading normal, or geometric for flat meshes)
  Vec3 geometric;  // winding normal of the first triangle, for the side flip
};

constexpr float kSmoothWeldCos = 0.9f;  // smooth meshes: shading normals within ~25 degrees
constexpr float kFlatWeldCos = 0.999f;  // flat meshes: (nearly) coplanar faces only

}  // namespace

RadiosityMesh::RadiosityMesh(const Scene& scene, const Accel& accel,
                             const RadiosityMeshSettings& settings,
                             const std::function<bool(const Material&)>& meshed,
                             std::vector<std::string>* warnings) {
  // World-space triangles, in Embree instance order.
  std::vector<TriangleInput> input;
  instance_first_triangle_.resize(accel.instance_count() + 1, 0);
  float largest = 0.0f;
  Vec3 lower(INFINITY), upper(-INFINITY);
  for (uint32_t id = 0; id < accel.instance_count(); ++id) {
    instance_first_triangle_[id] = static_cast<uint32_t>(input.size());
    const Instance& inst = scene.instances[accel.scene_instance(id)];
    const Mesh& mesh = scene.meshes[inst.mesh];
    for (uint32_t tri = 0; tri < mesh.triangle_count(); ++tri) {
      TriangleInput t;
      for (int k = 0; k < 3; ++k)
        t.world[k] = inst.object_to_world.point(mesh.positions[mesh.indices[3 * tri + k]]);
      t.area = 0.5f * length(cross(t.world[1] - t.world[0], t.world[2] - t.world[0]));
      t.longest = std::max({length(t.world[1] - t.world[0]), length(t.world[2] - t.world[1]),
                            length(t.world[0] - t.world[2])});
      t.meshed = t.area > 0.0f && std::isfinite(t.area) && std::isfinite(t.longest) &&
                 meshed(accel.triangle_material(id, tri));
      t.centroid = (t.world[0] + t.world[1] + t.world[2]) * (1.0f / 3.0f);
      t.instance = id;
      t.slot = mesh.material_slots.empty() ? 0u : static_cast<uint32_t>(mesh.material_slots[tri]);
      const Vec3 g = cross(t.world[1] - t.world[0], t.world[2] - t.world[0]);
      const float ax[3] = {std::fabs(g.x), std::fabs(g.y), std::fabs(g.z)};
      const int axis = ax[0] >= ax[1] && ax[0] >= ax[2] ? 0 : ax[1] >= ax[2] ? 1 : 2;
      t.axis = static_cast<uint8_t>(2 * axis + (g[axis] < 0.0f ? 1 : 0));
      if (t.meshed) {
        largest = std::max(largest, t.longest);
        total_area_ += t.area;
        for (const Vec3& p : t.world) lower = min(lower, p), upper = max(upper, p);
      }
      input.push_back(t);
    }
  }
  instance_first_triangle_[accel.instance_count()] = static_cast<uint32_t>(input.size());

  // Patch size: the user's, or automatic (about auto_elements patches, and no more than the
  // ray budget can light well); coarsened if the patch count would exceed max_elements.
  Sizing sizing;
  sizing.max_subdivisions = std::max<uint32_t>(settings.max_subdivisions, 1);
  sizing.cluster_fraction = std::isfinite(settings.cluster_fraction)
                                ? std::clamp(settings.cluster_fraction, 0.0f, 1.0f)
                                : 0.5f;
  const uint32_t max_sub = sizing.max_subdivisions;
  const bool automatic = !(settings.patch_size > 0.0f && std::isfinite(settings.patch_size));
  size_t ray_cap = SIZE_MAX;
  if (settings.rays > 0)
    ray_cap = std::max<size_t>(
        settings.min_patches,
        static_cast<size_t>(settings.rays / std::max<uint32_t>(settings.min_rays_per_patch, 1)));
  if (largest > 0.0f) {
    // The bisection's upper end: large enough to put every small triangle in a few clusters.
    const float extent = std::max(largest, length(upper - lower));
    float size = automatic ? size_for_count(input, std::min(settings.auto_elements, ray_cap),
                                            largest, extent, sizing)
                           : settings.patch_size;
    const size_t count = patch_count_for(input, size, sizing);
    if (count > settings.max_elements) {
      const float coarser = size_for_count(input, settings.max_elements, largest, extent, sizing);
      if (warnings)
        warnings->push_back("Radiosity: patch size " + std::to_string(size) +
                            " would make more than " + std::to_string(settings.max_elements) +
                            " patches; using " + std::to_string(coarser));
      size = coarser;
    } else if (!automatic && count > ray_cap && warnings) {
      warnings->push_back("Radiosity: patch size " + std::to_string(size) + " makes " +
                          std::to_string(count) + " patches for " + std::to_string(settings.rays) +
                          " rays (fewer than " + std::to_string(settings.min_rays_per_patch) +
                          " rays per patch): expect noise; use more rays or larger patches");
    }
    patch_size_ = size;
  }

  // Local refinement: the split patches (indices of the unrefined mesh, whose numbering the loop
  // below reproduces) and the instances that hold one of them.
  std::vector<uint32_t> split;
  if (settings.split_patches) {
    split = *settings.split_patches;
    std::sort(split.begin(), split.end());
    split.erase(std::unique(split.begin(), split.end()), split.end());
  }
  std::vector<uint8_t> instance_refined(accel.instance_count(), 0);
  if (!split.empty()) {
    std::unordered_map<ClusterKey, uint32_t, ClusterKeyHash> clusters;
    uint32_t base = 0;
    for (const TriangleInput& in : input) {
      if (!in.meshed) continue;
      if (is_clustered(in, patch_size_, sizing)) {
        if (clusters.try_emplace(cluster_key(in, patch_size_), base).second) ++base;
        continue;
      }
      const uint32_t n = subdivisions(in.longest, patch_size_, max_sub);
      const auto it = std::lower_bound(split.begin(), split.end(), base);
      if (it != split.end() && *it < base + n * n) instance_refined[in.instance] = 1;
      base += n * n;
    }
  }

  // Triangles and elements; every element of a subdivided triangle is a patch, clustered
  // triangles share their cluster's patch.
  triangles_.resize(input.size());
  uint32_t base_patches = 0;  // patch numbering without refinement
  uint32_t lattice_total = 0;
  std::unordered_map<ClusterKey, uint32_t, ClusterKeyHash> cluster_patch;
  uint32_t patches = 0;
  for (size_t t = 0; t < input.size(); ++t) {
    RadiosityTriangle& rt = triangles_[t];
    const TriangleInput& in = input[t];
    rt.p0 = in.world[0];
    rt.e1 = in.world[1] - in.world[0];
    rt.e2 = in.world[2] - in.world[0];
    rt.normal = normalize(cross(rt.e1, rt.e2));
    if (!in.meshed) continue;
    const uint32_t coarse = subdivisions(in.longest, patch_size_, max_sub);
    const bool clustered = is_clustered(in, patch_size_, sizing);
    const bool fine = !clustered && instance_refined[in.instance];
    const uint32_t n = fine ? 2 * coarse : coarse;
    rt.n = n;
    rt.element_area = in.area / static_cast<float>(n * n);
    rt.first_element = static_cast<uint32_t>(elements_.size());
    rt.first_lattice = lattice_total;
    lattice_total += (n + 1) * (n + 2) / 2;
    elements_.resize(elements_.size() + static_cast<size_t>(n) * n);
    element_patch_.resize(elements_.size());
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = 0; i + j < n; ++j) {
        elements_[rt.first_element + subdivision_element(n, i, j, true)] = {
            static_cast<uint32_t>(t), static_cast<uint16_t>(i), static_cast<uint16_t>(j), true};
        if (i + j + 1 < n)
          elements_[rt.first_element + subdivision_element(n, i, j, false)] = {
              static_cast<uint32_t>(t), static_cast<uint16_t>(i), static_cast<uint16_t>(j), false};
      }
    if (clustered) {
      rt.clustered = true;
      const auto found = cluster_patch.try_emplace(cluster_key(in, patch_size_), patches);
      if (found.second) ++patches, ++base_patches;
      element_patch_[rt.first_element] = found.first->second;
    } else if (!fine) {
      for (uint32_t k = 0; k < n * n; ++k) element_patch_[rt.first_element + k] = patches++;
      base_patches += n * n;
    } else {
      // Coarse element (i, j) in index order (upward ones, then downward) and its 4 elements on
      // the finer lattice: the 3 at its corners and the middle one, turned the other way.
      for (const bool up : {true, false})
        for (uint32_t i = 0; i < coarse; ++i)
          for (uint32_t j = 0; i + j + (up ? 0 : 1) < coarse; ++j) {
            const uint32_t a = 2 * i, b = 2 * j;
            const uint32_t fine_elements[4] = {up ? subdivision_element(n, a, b, true)
                                                  : subdivision_element(n, a + 1, b + 1, false),
                                               up ? subdivision_element(n, a + 1, b, true)
                                                  : subdivision_element(n, a, b + 1, false),
                                               up ? subdivision_element(n, a, b + 1, true)
                                                  : subdivision_element(n, a + 1, b, false),
                                               up ? subdivision_element(n, a, b, false)
                                                  : subdivision_element(n, a + 1, b + 1, true)};
            const bool split_here = std::binary_search(split.begin(), split.end(), base_patches++);
            if (split_here) ++split_count_;
            for (int k = 0; k < 4; ++k)
              element_patch_[rt.first_element + fine_elements[k]] =
                  split_here ? patches++ : patches;
            if (!split_here) ++patches;
          }
    }
  }
  cluster_count_ = cluster_patch.size();

  // Patch membership (elements in order), areas, centroids, normals.
  patch_first_.assign(patches + 1, 0);
  for (uint32_t p : element_patch_) ++patch_first_[p + 1];
  for (uint32_t p = 0; p < patches; ++p) patch_first_[p + 1] += patch_first_[p];
  patch_elements_.resize(elements_.size());
  {
    std::vector<uint32_t> fill(patch_first_.begin(), patch_first_.end() - 1);
    for (uint32_t e = 0; e < elements_.size(); ++e) patch_elements_[fill[element_patch_[e]]++] = e;
  }
  patch_cdf_.resize(elements_.size());
  patch_area_.assign(patches, 0.0f);
  patch_centroid_.assign(patches, Vec3(0.0f));
  patch_normal_.assign(patches, Vec3(0.0f));
  patch_instance_.assign(patches, 0);
  for (uint32_t p = 0; p < patches; ++p) {
    double area = 0.0;
    Vec3 centroid(0.0f), normal(0.0f);
    for (uint32_t k = patch_first_[p]; k < patch_first_[p + 1]; ++k) {
      const uint32_t e = patch_elements_[k];
      const float a = triangle_of(e).element_area;
      area += a;
      patch_cdf_[k] = static_cast<float>(area);
      centroid += (corner(e, 0) + corner(e, 1) + corner(e, 2)) * (a / 3.0f);
      normal += triangle_of(e).normal * a;
    }
    const uint32_t first = patch_elements_[patch_first_[p]];
    patch_area_[p] = static_cast<float>(area);
    patch_centroid_[p] = area > 0.0 ? centroid / static_cast<float>(area) : corner(first, 0);
    patch_normal_[p] =
        length_squared(normal) > 0.0f ? normalize(normal) : triangle_of(first).normal;
    patch_instance_[p] = input[elements_[first].triangle].instance;
  }

  // Welded vertices, per instance: lattice points at the same object-space position whose
  // normals agree share one vertex.
  lattice_.assign(lattice_total, 0);
  uint32_t vertices = 0;
  std::unordered_map<PositionKey, std::vector<WeldCluster>, PositionKeyHash> weld;
  for (uint32_t id = 0; id < accel.instance_count(); ++id) {
    weld.clear();
    const Instance& inst = scene.instances[accel.scene_instance(id)];
    const Mesh& mesh = scene.meshes[inst.mesh];
    const bool smooth = !mesh.corner_normals.empty();
    const float weld_cos = smooth ? kSmoothWeldCos : kFlatWeldCos;
    for (uint32_t tri = 0; tri < mesh.triangle_count(); ++tri) {
      const RadiosityTriangle& rt = triangles_[instance_first_triangle_[id] + tri];
      if (rt.n == 0) continue;
      const uint32_t n = rt.n;
      Vec3 p[3];
      for (int k = 0; k < 3; ++k) p[k] = mesh.positions[mesh.indices[3 * tri + k]];
      const Vec3 ng = normalize(cross(p[1] - p[0], p[2] - p[0]));
      for (uint32_t a = 0; a <= n; ++a)
        for (uint32_t b = 0; a + b <= n; ++b) {
          uint32_t& slot = lattice_[rt.first_lattice + subdivision_lattice(n, a, b)];
          bool interior;
          const Vec3 pos = lattice_position(p, n, a, b, &interior);
          if (interior) {
            slot = vertices++ << 1;
            continue;
          }
          Vec3 normal = ng;
          if (smooth) {
            const Vec3* cn = &mesh.corner_normals[3 * tri];
            const float b1 = static_cast<float>(a) / n, b2 = static_cast<float>(b) / n;
            const Vec3 s = cn[0] * (1.0f - b1 - b2) + cn[1] * b1 + cn[2] * b2;
            if (length_squared(s) > 0.0f && is_finite(s)) normal = normalize(s);
          }
          std::vector<WeldCluster>& clusters = weld[key_of(pos)];
          bool found = false;
          for (const WeldCluster& c : clusters) {
            const bool flip = dot(ng, c.geometric) < 0.0f;
            if (dot(flip ? -normal : normal, c.normal) > weld_cos) {
              slot = c.vertex << 1 | (flip ? 1u : 0u);
              found = true;
              break;
            }
          }
          if (!found) {
            clusters.push_back({vertices, normal, ng});
            slot = vertices++ << 1;
          }
        }
    }
  }
  vertex_count_ = vertices;
}

Vec3 RadiosityMesh::corner(uint32_t e, int k) const {
  const RadiosityElement& el = elements_[e];
  const RadiosityTriangle& t = triangles_[el.triangle];
  static constexpr int kUp[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  static constexpr int kDown[3][2] = {{1, 1}, {0, 1}, {1, 0}};
  const int* d = el.up ? kUp[k] : kDown[k];
  const float inv_n = 1.0f / static_cast<float>(t.n);
  return t.p0 + t.e1 * (static_cast<float>(el.i + d[0]) * inv_n) +
         t.e2 * (static_cast<float>(el.j + d[1]) * inv_n);
}

Vec3 RadiosityMesh::sample_point(uint32_t e, Vec2 u) const {
  const Vec3 c0 = corner(e, 0), c1 = corner(e, 1), c2 = corner(e, 2);
  // Uniform barycentrics by the square-root warp (Shirley 1990).
  // Shrunk by 1e-3 towards the centroid: a point computed exactly on an element's edge can
  // round to just behind the neighbouring face of a crease, and its ray would start outside.
  constexpr float kShrink = 1.0f - 1e-3f, kCentre = (1.0f - kShrink) / 3.0f;
  const float su = std::sqrt(u.x);
  const float b1 = kCentre + kShrink * su * (1.0f - u.y), b2 = kCentre + kShrink * su * u.y;
  return c0 + (c1 - c0) * b1 + (c2 - c0) * b2;
}

Vec3 RadiosityMesh::sample_patch(uint32_t p, float u_element, Vec2 u, uint32_t* element) const {
  const uint32_t begin = patch_first_[p], end = patch_first_[p + 1];
  uint32_t k = begin;
  if (end - begin > 1) {
    const float target = u_element * patch_cdf_[end - 1];
    k = static_cast<uint32_t>(
        std::upper_bound(patch_cdf_.begin() + begin, patch_cdf_.begin() + end, target) -
        patch_cdf_.begin());
    k = std::min(k, end - 1);
  }
  *element = patch_elements_[k];
  return sample_point(*element, u);
}

uint32_t RadiosityMesh::triangle_index(uint32_t instance, uint32_t primitive) const {
  if (instance + 1 >= instance_first_triangle_.size()) return UINT32_MAX;
  const uint32_t index = instance_first_triangle_[instance] + primitive;
  return index < instance_first_triangle_[instance + 1] ? index : UINT32_MAX;
}

uint32_t RadiosityMesh::lattice_vertex(const RadiosityTriangle& t, uint32_t a, uint32_t b,
                                       bool* flip) const {
  const uint32_t packed = lattice_[t.first_lattice + subdivision_lattice(t.n, a, b)];
  *flip = (packed & 1u) != 0;
  return packed >> 1;
}

void RadiosityMesh::element_vertices(uint32_t e, uint32_t vertex[3], bool flip[3]) const {
  const RadiosityElement& el = elements_[e];
  const RadiosityTriangle& t = triangles_[el.triangle];
  const uint32_t i = el.i, j = el.j;
  if (el.up) {
    vertex[0] = lattice_vertex(t, i, j, &flip[0]);
    vertex[1] = lattice_vertex(t, i + 1, j, &flip[1]);
    vertex[2] = lattice_vertex(t, i, j + 1, &flip[2]);
  } else {
    vertex[0] = lattice_vertex(t, i + 1, j + 1, &flip[0]);
    vertex[1] = lattice_vertex(t, i, j + 1, &flip[1]);
    vertex[2] = lattice_vertex(t, i + 1, j, &flip[2]);
  }
}

bool RadiosityMesh::locate(uint32_t instance, uint32_t primitive, float u, float v,
                           RadiosityLocation* out) const {
  const uint32_t index = triangle_index(instance, primitive);
  if (index == UINT32_MAX) return false;
  const RadiosityTriangle& t = triangles_[index];
  if (t.n == 0) return false;
  const uint32_t n = t.n;
  const float fu = std::clamp(u, 0.0f, 1.0f) * n, fv = std::clamp(v, 0.0f, 1.0f) * n;
  uint32_t i = std::min(static_cast<uint32_t>(fu), n - 1);
  uint32_t j = std::min(static_cast<uint32_t>(fv), n - 1);
  if (i + j > n - 1) j = n - 1 - i;  // on the hypotenuse, after rounding
  const float ru = fu - static_cast<float>(i), rv = fv - static_cast<float>(j);
  const bool up = ru + rv <= 1.0f || i + j == n - 1;
  out->element = t.first_element + subdivision_element(n, i, j, up);
  float w[3];
  if (up) {
    w[0] = 1.0f - ru - rv, w[1] = ru, w[2] = rv;
  } else {
    w[1] = 1.0f - ru, w[2] = 1.0f - rv;
    w[0] = 1.0f - w[1] - w[2];
  }
  float sum = 0.0f;
  for (float& x : w) sum += (x = std::clamp(x, 0.0f, 1.0f));
  for (int k = 0; k < 3; ++k) out->weight[k] = sum > 0.0f ? w[k] / sum : 1.0f / 3.0f;
  element_vertices(out->element, out->vertex, out->flip);
  return true;
}

}  // namespace photon

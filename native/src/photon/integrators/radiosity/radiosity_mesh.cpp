#include "photon/integrators/radiosity/radiosity_mesh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <unordered_map>

#include "photon/base/rng.h"

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

  // Local refinement: the split cells and the levels of each instance (as deep as its deepest
  // split, so the instance's triangles share one lattice and their edges weld).
  std::vector<RadiosityCell> split;
  std::vector<uint8_t> instance_levels(accel.instance_count(), 0);
  const uint32_t max_levels = std::min<uint32_t>(settings.max_levels, 5);
  if (settings.split_cells) {
    for (const RadiosityCell& c : *settings.split_cells) {
      if (c.triangle >= input.size() || c.level >= max_levels) continue;
      const TriangleInput& in = input[c.triangle];
      if (!in.meshed || is_clustered(in, patch_size_, sizing)) continue;
      split.push_back(c);
      uint8_t& levels = instance_levels[in.instance];
      levels = std::max<uint8_t>(levels, static_cast<uint8_t>(c.level + 1));
    }
    std::sort(split.begin(), split.end());
    split.erase(std::unique(split.begin(), split.end()), split.end());
  }

  // Triangles and elements; every element of a subdivided triangle is a patch, clustered
  // triangles share their cluster's patch.
  triangles_.resize(input.size());
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
    const uint32_t levels = clustered ? 0u : instance_levels[in.instance];
    const uint32_t n = coarse << levels;
    rt.n = n;
    rt.levels = static_cast<uint8_t>(levels);
    rt.element_area = in.area / static_cast<float>(n * n);
    rt.first_element = static_cast<uint32_t>(elements_.size());
    rt.first_lattice = lattice_total;
    lattice_total += (n + 1) * (n + 2) / 2;
    if (levels > 0) {
      // Leaf cells of the hierarchy under each coarse cell (in index order), depth first.
      rt.first_cell = static_cast<uint32_t>(cell_element_.size());
      cell_element_.resize(cell_element_.size() + static_cast<size_t>(n) * n);
      std::vector<RadiosityCell> stack;
      for (const bool up : {false, true})  // popped in reverse: upward cells first
        for (uint32_t i = coarse; i-- > 0;)
          for (uint32_t j = coarse; j-- > 0;)
            if (i + j + (up ? 0u : 1u) < coarse)
              stack.push_back({static_cast<uint32_t>(t), static_cast<uint16_t>(i),
                               static_cast<uint16_t>(j), 0, up});
      while (!stack.empty()) {
        const RadiosityCell c = stack.back();
        stack.pop_back();
        const uint16_t a = static_cast<uint16_t>(2 * c.i), b = static_cast<uint16_t>(2 * c.j);
        const uint8_t l = static_cast<uint8_t>(c.level + 1);
        if (std::binary_search(split.begin(), split.end(), c)) {
          ++split_count_;
          // Children: the three at the corners and the middle one, turned the other way; pushed
          // in reverse so they come out in this order.
          const RadiosityCell children[4] = {
              c.up ? RadiosityCell{c.triangle, a, b, l, true}
                   : RadiosityCell{c.triangle, static_cast<uint16_t>(a + 1),
                                   static_cast<uint16_t>(b + 1), l, false},
              c.up ? RadiosityCell{c.triangle, static_cast<uint16_t>(a + 1), b, l, true}
                   : RadiosityCell{c.triangle, a, static_cast<uint16_t>(b + 1), l, false},
              c.up ? RadiosityCell{c.triangle, a, static_cast<uint16_t>(b + 1), l, true}
                   : RadiosityCell{c.triangle, static_cast<uint16_t>(a + 1), b, l, false},
              c.up ? RadiosityCell{c.triangle, a, b, l, false}
                   : RadiosityCell{c.triangle, static_cast<uint16_t>(a + 1),
                                   static_cast<uint16_t>(b + 1), l, true}};
          for (int k = 3; k >= 0; --k) stack.push_back(children[k]);
          continue;
        }
        const uint32_t e = static_cast<uint32_t>(elements_.size());
        elements_.push_back({c.triangle, c.i, c.j, c.level, c.up});
        element_patch_.push_back(patches++);
        // The lattice cells it covers: its cell refined down to the lattice.
        std::vector<RadiosityCell> cover = {c};
        while (!cover.empty()) {
          const RadiosityCell d = cover.back();
          cover.pop_back();
          if (d.level == levels) {
            cell_element_[rt.first_cell + subdivision_element(n, d.i, d.j, d.up)] = e;
            continue;
          }
          const uint16_t da = static_cast<uint16_t>(2 * d.i), db = static_cast<uint16_t>(2 * d.j);
          const uint8_t dl = static_cast<uint8_t>(d.level + 1);
          if (d.up) {
            cover.push_back({d.triangle, da, db, dl, true});
            cover.push_back({d.triangle, static_cast<uint16_t>(da + 1), db, dl, true});
            cover.push_back({d.triangle, da, static_cast<uint16_t>(db + 1), dl, true});
            cover.push_back({d.triangle, da, db, dl, false});
          } else {
            cover.push_back({d.triangle, static_cast<uint16_t>(da + 1),
                             static_cast<uint16_t>(db + 1), dl, false});
            cover.push_back({d.triangle, da, static_cast<uint16_t>(db + 1), dl, false});
            cover.push_back({d.triangle, static_cast<uint16_t>(da + 1), db, dl, false});
            cover.push_back({d.triangle, static_cast<uint16_t>(da + 1),
                             static_cast<uint16_t>(db + 1), dl, true});
          }
        }
      }
      continue;
    }
    elements_.resize(elements_.size() + static_cast<size_t>(n) * n);
    element_patch_.resize(elements_.size());
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = 0; i + j < n; ++j) {
        elements_[rt.first_element + subdivision_element(n, i, j, true)] = {
            static_cast<uint32_t>(t), static_cast<uint16_t>(i), static_cast<uint16_t>(j), 0, true};
        if (i + j + 1 < n)
          elements_[rt.first_element + subdivision_element(n, i, j, false)] = {
              static_cast<uint32_t>(t), static_cast<uint16_t>(i), static_cast<uint16_t>(j), 0,
              false};
      }
    if (clustered) {
      rt.clustered = true;
      const auto found = cluster_patch.try_emplace(cluster_key(in, patch_size_), patches);
      if (found.second) ++patches;
      element_patch_[rt.first_element] = found.first->second;
    } else {
      for (uint32_t k = 0; k < n * n; ++k) element_patch_[rt.first_element + k] = patches++;
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
      const float a = this->area(e);
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
  const float inv_n = 1.0f / static_cast<float>(t.n >> (t.levels - el.level));
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

namespace {
// Lattice coordinates of corner k of element (i, j, up), on its own grid.
void element_corner(const RadiosityElement& el, int k, uint32_t* a, uint32_t* b) {
  static constexpr uint32_t kUp[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  static constexpr uint32_t kDown[3][2] = {{1, 1}, {0, 1}, {1, 0}};
  const uint32_t* d = el.up ? kUp[k] : kDown[k];
  *a = el.i + d[0];
  *b = el.j + d[1];
}
}  // namespace

void RadiosityMesh::element_vertices(uint32_t e, uint32_t vertex[3], bool flip[3]) const {
  const RadiosityElement& el = elements_[e];
  const RadiosityTriangle& t = triangles_[el.triangle];
  const uint32_t shift = t.levels - el.level;
  for (int k = 0; k < 3; ++k) {
    uint32_t a, b;
    element_corner(el, k, &a, &b);
    vertex[k] = lattice_vertex(t, a << shift, b << shift, &flip[k]);
  }
}

void RadiosityMesh::edge_vertices(uint32_t e, int k, std::vector<uint32_t>* vertex,
                                  std::vector<uint8_t>* flip) const {
  const RadiosityElement& el = elements_[e];
  const RadiosityTriangle& t = triangles_[el.triangle];
  const uint32_t shift = t.levels - el.level, span = 1u << shift;
  uint32_t a0, b0, a1, b1;
  element_corner(el, k, &a0, &b0);
  element_corner(el, (k + 1) % 3, &a1, &b1);
  vertex->clear();
  flip->clear();
  for (uint32_t s = 0; s <= span; ++s) {
    // (a0 + (a1 - a0) s / span) << shift, in integers (the ends differ by at most 1 per axis).
    const uint32_t a = (a0 << shift) + s * a1 - s * a0, b = (b0 << shift) + s * b1 - s * b0;
    bool f;
    vertex->push_back(lattice_vertex(t, a, b, &f));
    flip->push_back(f ? 1 : 0);
  }
}

bool RadiosityMesh::locate(uint32_t instance, uint32_t primitive, float u, float v,
                           RadiosityLocation* out) const {
  const uint32_t index = triangle_index(instance, primitive);
  if (index == UINT32_MAX) return false;
  const RadiosityTriangle& t = triangles_[index];
  if (t.n == 0) return false;
  uint32_t n = t.n;
  float fu = std::clamp(u, 0.0f, 1.0f) * n, fv = std::clamp(v, 0.0f, 1.0f) * n;
  uint32_t i = std::min(static_cast<uint32_t>(fu), n - 1);
  uint32_t j = std::min(static_cast<uint32_t>(fv), n - 1);
  if (i + j > n - 1) j = n - 1 - i;  // on the hypotenuse, after rounding
  float ru = fu - static_cast<float>(i), rv = fv - static_cast<float>(j);
  bool up = ru + rv <= 1.0f || i + j == n - 1;
  const uint32_t cell = subdivision_element(n, i, j, up);
  if (t.first_cell == UINT32_MAX) {
    out->element = t.first_element + cell;
  } else {
    // Locally refined: the element covering the lattice cell, and the point's place in it.
    out->element = cell_element_[t.first_cell + cell];
    const RadiosityElement& el = elements_[out->element];
    n = t.n >> (t.levels - el.level);
    fu = std::clamp(u, 0.0f, 1.0f) * n, fv = std::clamp(v, 0.0f, 1.0f) * n;
    ru = fu - static_cast<float>(el.i), rv = fv - static_cast<float>(el.j);
    up = el.up;
  }
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

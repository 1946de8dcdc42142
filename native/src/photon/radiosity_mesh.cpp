#include "photon/radiosity_mesh.h"

#include <cstring>
#include <unordered_map>

#include "photon/rng.h"

namespace photon {
namespace {

struct TriangleInput {
  Vec3 world[3];
  float longest = 0.0f;  // world-space longest edge
  float area = 0.0f;
  bool meshed = false;
};

uint32_t subdivisions(float longest, float patch_size, uint32_t max_subdivisions) {
  if (!(patch_size > 0.0f)) return 1;
  const double n = std::ceil(static_cast<double>(longest) / patch_size);
  return static_cast<uint32_t>(std::clamp(n, 1.0, static_cast<double>(max_subdivisions)));
}

size_t element_count_for(const std::vector<TriangleInput>& tris, float patch_size,
                         uint32_t max_subdivisions) {
  size_t count = 0;
  for (const TriangleInput& t : tris)
    if (t.meshed) {
      const size_t n = subdivisions(t.longest, patch_size, max_subdivisions);
      count += n * n;
    }
  return count;
}

// The smallest patch size (within 1%) whose element count does not exceed `target`, by
// bisection on log(size): the count falls monotonically as the size grows.
float size_for_count(const std::vector<TriangleInput>& tris, size_t target, float largest,
                     uint32_t max_subdivisions) {
  if (element_count_for(tris, largest, max_subdivisions) >= target) return largest;
  double lo = std::log(static_cast<double>(largest) * 1e-6),
         hi = std::log(static_cast<double>(largest));
  for (int k = 0; k < 40 && hi - lo > 0.01; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (element_count_for(tris, static_cast<float>(std::exp(mid)), max_subdivisions) > target)
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
      if (t.meshed) {
        largest = std::max(largest, t.longest);
        total_area_ += t.area;
      }
      input.push_back(t);
    }
  }
  instance_first_triangle_[accel.instance_count()] = static_cast<uint32_t>(input.size());

  // Patch size: the user's, or automatic (about auto_elements elements); coarsened if the
  // element count would exceed max_elements.
  const uint32_t max_sub = std::max<uint32_t>(settings.max_subdivisions, 1);
  if (largest > 0.0f) {
    float size = settings.patch_size > 0.0f && std::isfinite(settings.patch_size)
                     ? settings.patch_size
                     : size_for_count(input, settings.auto_elements, largest, max_sub);
    if (element_count_for(input, size, max_sub) > settings.max_elements) {
      const float coarser = size_for_count(input, settings.max_elements, largest, max_sub);
      if (warnings)
        warnings->push_back("Radiosity: patch size " + std::to_string(size) +
                            " would make more than " + std::to_string(settings.max_elements) +
                            " elements; using " + std::to_string(coarser));
      size = coarser;
    }
    patch_size_ = size;
  }

  // Triangles and elements.
  triangles_.resize(input.size());
  uint32_t lattice_total = 0;
  for (size_t t = 0; t < input.size(); ++t) {
    RadiosityTriangle& rt = triangles_[t];
    const TriangleInput& in = input[t];
    rt.p0 = in.world[0];
    rt.e1 = in.world[1] - in.world[0];
    rt.e2 = in.world[2] - in.world[0];
    rt.normal = normalize(cross(rt.e1, rt.e2));
    if (!in.meshed) continue;
    const uint32_t n = subdivisions(in.longest, patch_size_, max_sub);
    rt.n = n;
    rt.element_area = in.area / static_cast<float>(n * n);
    rt.first_element = static_cast<uint32_t>(elements_.size());
    rt.first_lattice = lattice_total;
    lattice_total += (n + 1) * (n + 2) / 2;
    elements_.resize(elements_.size() + static_cast<size_t>(n) * n);
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = 0; i + j < n; ++j) {
        elements_[rt.first_element + subdivision_element(n, i, j, true)] = {
            static_cast<uint32_t>(t), static_cast<uint16_t>(i), static_cast<uint16_t>(j), true};
        if (i + j + 1 < n)
          elements_[rt.first_element + subdivision_element(n, i, j, false)] = {
              static_cast<uint32_t>(t), static_cast<uint16_t>(i), static_cast<uint16_t>(j), false};
      }
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

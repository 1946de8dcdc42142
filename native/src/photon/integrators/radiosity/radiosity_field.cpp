#include "photon/integrators/radiosity/radiosity_field.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "photon/base/rng.h"

namespace photon {
namespace {

RadiosityPower scaled(const RadiosityPower& p, float s) {
  return {p.direct * s, p.caustic * s, p.indirect * s};
}

void add(RadiosityPower* a, const RadiosityPower& b) {
  a->direct += b.direct;
  a->caustic += b.caustic;
  a->indirect += b.indirect;
}

// Kernel radius of the cluster reconstruction, in patch sizes: about 3 to 7 patch centroids
// fall inside it on a surface, enough to hide the voxel outlines, little enough to keep shading.
constexpr float kKernelRadius = 1.5f;
// Patches whose normal is more than 60 degrees from the vertex's do not contribute (creases,
// the other side of a thin shell).
constexpr float kKernelMinCos = 0.5f;

struct CellKey {
  uint32_t instance;
  int32_t x, y, z;
  bool operator==(const CellKey& o) const { return std::memcmp(this, &o, sizeof o) == 0; }
};
struct CellKeyHash {
  size_t operator()(const CellKey& k) const {
    return static_cast<size_t>(
        hash_combine(hash_combine(k.instance, static_cast<uint32_t>(k.x)),
                     hash_combine(static_cast<uint32_t>(k.y), static_cast<uint32_t>(k.z))));
  }
};
int32_t cell_of(float x, float cell) {
  return static_cast<int32_t>(std::clamp(std::floor(static_cast<double>(x) / cell), -1e9, 1e9));
}

struct SmoothVertex {
  uint32_t vertex;
  uint32_t instance;
  Vec3 position, normal;  // normal of the vertex's front side
};

}  // namespace

RadiosityField::RadiosityField(const RadiosityMesh& mesh,
                               const std::vector<RadiosityPower>& side_power) {
  const size_t elements = mesh.element_count(), patches = mesh.patch_count();
  if (side_power.size() != 2 * patches || patches == 0) return;
  patch_.resize(2 * patches);
  for (uint32_t p = 0; p < patches; ++p) {
    const float area = mesh.patch_area(p);
    for (uint32_t side = 0; side < 2; ++side)
      patch_[2 * p + side] = scaled(side_power[2 * p + side], area > 0.0f ? 1.0f / area : 0.0f);
  }
  element_patch_.resize(elements);
  vertex_.assign(2 * mesh.vertex_count(), RadiosityPower{});
  std::vector<double> vertex_area(mesh.vertex_count(), 0.0);
  std::vector<uint8_t> smooth(mesh.vertex_count(), 0);
  std::vector<SmoothVertex> smooth_vertices;
  for (uint32_t e = 0; e < elements; ++e) {
    const uint32_t p = mesh.patch_of(e);
    element_patch_[e] = p;
    const float area = mesh.area(e);
    // The element's share of its patch's power: P itself for a one-element patch.
    const bool single = mesh.patch_element_count(p) == 1;
    RadiosityPower power[2];
    for (uint32_t side = 0; side < 2; ++side)
      power[side] = single ? side_power[2 * p + side] : scaled(patch_[2 * p + side], area);
    // Sum of P over the elements around a vertex / sum of their areas = area-weighted mean B.
    uint32_t vertex[3];
    bool flip[3];
    mesh.element_vertices(e, vertex, flip);
    const bool clustered = mesh.patch_clustered(p);
    for (int k = 0; k < 3; ++k) {
      vertex_area[vertex[k]] += area;
      for (uint32_t side = 0; side < 2; ++side)
        add(&vertex_[2 * vertex[k] + (side ^ (flip[k] ? 1u : 0u))], power[side]);
      if (clustered && !smooth[vertex[k]]) {
        smooth[vertex[k]] = 1;
        smooth_vertices.push_back({vertex[k], mesh.patch_instance(p), mesh.corner(e, k),
                                   flip[k] ? -mesh.normal(e) : mesh.normal(e)});
      }
    }
  }
  for (size_t v = 0; v < vertex_area.size(); ++v) {
    const float inv = vertex_area[v] > 0.0 ? static_cast<float>(1.0 / vertex_area[v]) : 0.0f;
    vertex_[2 * v] = scaled(vertex_[2 * v], inv);
    vertex_[2 * v + 1] = scaled(vertex_[2 * v + 1], inv);
  }
  // Local refinement leaves T-vertices: corners of small elements inside the edge of a larger
  // neighbour. Each takes the value interpolated along that edge, so both sides of the edge
  // interpolate the same line and the shading has no cracks (Cohen & Wallace 1993, ch. 8, on
  // T-vertices); larger elements first, as their edges' ends may be T-vertices of larger ones.
  std::vector<std::pair<uint32_t, uint32_t>> coarse;  // (levels below the lattice, element)
  for (uint32_t e = 0; e < elements; ++e)
    if (mesh.element_shift(e) > 0) coarse.push_back({mesh.element_shift(e), e});
  std::sort(coarse.begin(), coarse.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<uint32_t> edge;
  std::vector<uint8_t> edge_flip;
  for (const auto& c : coarse)
    for (int k = 0; k < 3; ++k) {
      mesh.edge_vertices(c.second, k, &edge, &edge_flip);
      const size_t span = edge.size() - 1;
      for (uint32_t side = 0; side < 2; ++side) {
        const RadiosityPower a = vertex_[2 * edge[0] + (side ^ edge_flip[0])];
        const RadiosityPower b = vertex_[2 * edge[span] + (side ^ edge_flip[span])];
        for (size_t s = 1; s < span; ++s) {
          const float t = static_cast<float>(s) / static_cast<float>(span);
          RadiosityPower v = scaled(a, 1.0f - t);
          add(&v, scaled(b, t));
          vertex_[2 * edge[s] + (side ^ edge_flip[s])] = v;
        }
      }
    }

  const float radius = kKernelRadius * mesh.patch_size();
  if (smooth_vertices.empty() || !(radius > 0.0f) || !std::isfinite(radius)) return;

  // Patches by grid cell (edge = kernel radius) of their centroid, per instance.
  std::unordered_map<CellKey, std::vector<uint32_t>, CellKeyHash> grid;
  for (uint32_t p = 0; p < patches; ++p) {
    const Vec3 c = mesh.patch_centroid(p);
    grid[{mesh.patch_instance(p), cell_of(c.x, radius), cell_of(c.y, radius), cell_of(c.z, radius)}]
        .push_back(p);
  }
  tbb::parallel_for(size_t(0), smooth_vertices.size(), [&](size_t i) {
    const SmoothVertex& sv = smooth_vertices[i];
    const int32_t cx = cell_of(sv.position.x, radius), cy = cell_of(sv.position.y, radius),
                  cz = cell_of(sv.position.z, radius);
    RadiosityPower sum[2];
    double weight = 0.0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto cell = grid.find({sv.instance, cx + dx, cy + dy, cz + dz});
          if (cell == grid.end()) continue;
          for (uint32_t p : cell->second) {
            const float cos = dot(sv.normal, mesh.patch_normal(p));
            const float d = length(mesh.patch_centroid(p) - sv.position);
            if (!(cos > kKernelMinCos) || !(d < radius)) continue;
            const float w = mesh.patch_area(p) * (1.0f - d / radius) * cos;
            weight += w;
            for (uint32_t side = 0; side < 2; ++side)
              add(&sum[side], scaled(patch_[2 * p + side], w));
          }
        }
    if (!(weight > 0.0)) return;  // keep the area-weighted mean
    const float inv = static_cast<float>(1.0 / weight);
    vertex_[2 * sv.vertex] = scaled(sum[0], inv);
    vertex_[2 * sv.vertex + 1] = scaled(sum[1], inv);
  });
}

RadiosityPower RadiosityField::radiosity_at(const RadiosityLocation& where, uint32_t side) const {
  RadiosityPower b;
  if (empty()) return b;
  for (int k = 0; k < 3; ++k)
    add(&b,
        scaled(vertex_[2 * where.vertex[k] + (side ^ (where.flip[k] ? 1u : 0u))], where.weight[k]));
  return b;
}

}  // namespace photon

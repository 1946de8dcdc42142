#include "photon/scene/vertex_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace photon {
namespace {

bool polygon_in_range(const PolygonMeshView& mesh, size_t poly) {
  const int64_t start = mesh.poly_loop_starts[poly], total = mesh.poly_loop_totals[poly];
  if (start < 0 || total < 3 || static_cast<uint64_t>(start + total) > mesh.loop_count)
    return false;
  for (int64_t l = start; l < start + total; ++l) {
    const int32_t v = mesh.loop_vertices[l];
    if (v < 0 || static_cast<size_t>(v) >= mesh.vertex_count) return false;
  }
  return true;
}

// Unit vector from a to b, or zero when they coincide.
Vec3 edge_direction(const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const float l = length(d);
  return l > 0.0f ? d / l : Vec3(0.0f);
}

}  // namespace

Vec3 polygon_normal(const Vec3* positions, const int32_t* loop_vertices, size_t corners) {
  const auto p = [&](size_t i) { return positions[loop_vertices[i]]; };
  Vec3 n(0.0f);
  if (corners == 3) {
    n = cross(p(0) - p(1), p(1) - p(2));
  } else if (corners == 4) {
    n = cross(p(0) - p(2), p(1) - p(3));
  } else {
    // Newell's method: the sum of the edges' cross products, exact for planar polygons and
    // a least-squares plane's normal for the rest.
    Vec3 prev = p(corners - 1);
    for (size_t i = 0; i < corners; ++i) {
      const Vec3 cur = p(i);
      n += Vec3((prev.y - cur.y) * (prev.z + cur.z), (prev.z - cur.z) * (prev.x + cur.x),
                (prev.x - cur.x) * (prev.y + cur.y));
      prev = cur;
    }
  }
  const float l = length(n);
  return l > 0.0f && std::isfinite(l) ? n / l : Vec3(0.0f);
}

std::vector<Vec3> angle_weighted_vertex_normals(const PolygonMeshView& mesh) {
  // Each loop's weighted normal first (polygons in parallel, each loop written once), then the
  // per-vertex sums in loop order: the order of every float addition is fixed.
  std::vector<Vec3> loop_terms(mesh.loop_count, Vec3(0.0f));
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, mesh.poly_count, 1 << 12),
      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t poly = range.begin(); poly < range.end(); ++poly) {
          if (!polygon_in_range(mesh, poly)) continue;
          const size_t start = mesh.poly_loop_starts[poly], total = mesh.poly_loop_totals[poly];
          const int32_t* verts = mesh.loop_vertices + start;
          const Vec3 n = polygon_normal(mesh.positions, verts, total);
          if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) continue;  // degenerate or not finite
          Vec3 to_prev = edge_direction(mesh.positions[verts[0]], mesh.positions[verts[total - 1]]);
          for (size_t i = 0; i < total; ++i) {
            const Vec3& here = mesh.positions[verts[i]];
            const Vec3 to_next = edge_direction(here, mesh.positions[verts[(i + 1) % total]]);
            const float angle = std::acos(std::clamp(dot(to_prev, to_next), -1.0f, 1.0f));
            loop_terms[start + i] = n * angle;
            to_prev = -to_next;
          }
        }
      });
  std::vector<Vec3> normals(mesh.vertex_count, Vec3(0.0f));
  for (size_t l = 0; l < mesh.loop_count; ++l) {
    const int32_t v = mesh.loop_vertices[l];
    if (v >= 0 && static_cast<size_t>(v) < mesh.vertex_count) normals[v] += loop_terms[l];
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.vertex_count, 1 << 14),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t v = range.begin(); v < range.end(); ++v) {
                        const float l = length(normals[v]);
                        if (l > 0.0f && std::isfinite(l)) {
                          normals[v] = normals[v] / l;
                        } else {  // loose: the position's direction, or none when not finite
                          const Vec3 p = normalize(mesh.positions[v]);
                          normals[v] = is_finite(p) ? p : Vec3(0.0f);
                        }
                      }
                    });
  return normals;
}

std::vector<Vec3> smooth_and_flat_loop_normals(const PolygonMeshView& mesh,
                                               const uint8_t* poly_smooth,
                                               const std::vector<Vec3>& vertex_normals) {
  std::vector<Vec3> normals(mesh.loop_count, Vec3(0.0f));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.poly_count, 1 << 12),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t poly = range.begin(); poly < range.end(); ++poly) {
                        if (!polygon_in_range(mesh, poly)) continue;
                        const size_t start = mesh.poly_loop_starts[poly],
                                     total = mesh.poly_loop_totals[poly];
                        const int32_t* verts = mesh.loop_vertices + start;
                        if (poly_smooth[poly]) {
                          for (size_t i = 0; i < total; ++i)
                            normals[start + i] = vertex_normals[verts[i]];
                        } else {
                          const Vec3 n = polygon_normal(mesh.positions, verts, total);
                          for (size_t i = 0; i < total; ++i) normals[start + i] = n;
                        }
                      }
                    });
  return normals;
}

}  // namespace photon

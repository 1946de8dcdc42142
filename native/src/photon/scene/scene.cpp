#include "photon/scene/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <functional>

namespace photon {

const Material& Scene::default_material() {
  static const Material kDefault = Material::diffuse(Vec3(0.8f), "default");
  return kDefault;
}

void Camera::set_camera_to_world(const Transform& xf) {
  Vec3 x = xf.column(0), y = xf.column(1), z = xf.column(2);
  const Vec3 t = xf.column(3);
  z = normalize(z);
  y = normalize(y - z * dot(y, z));
  x = cross(y, z);
  const bool ok =
      is_finite(x) && is_finite(y) && is_finite(z) && is_finite(t) && length_squared(x) > 0.5f;
  if (!ok) {
    x = Vec3(1, 0, 0);
    y = Vec3(0, 1, 0);
    z = Vec3(0, 0, 1);
  }
  const Vec3 pos = is_finite(t) ? t : Vec3(0.0f);
  const float rows[12] = {x.x, y.x, z.x, pos.x, x.y, y.y, z.y, pos.y, x.z, y.z, z.z, pos.z};
  camera_to_world = Transform::from_rows(rows);
}

MeshCleanupReport clean_mesh(Mesh* mesh) {
  // Vertices and triangles are checked in parallel (each verdict depends on its own data only,
  // so the result does not depend on the thread count); only meshes that lose triangles pay
  // for the serial compaction.
  MeshCleanupReport report;
  const size_t vertex_count = mesh->positions.size();
  std::vector<uint8_t> bad_vertex(vertex_count, 0);
  report.non_finite_vertices = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, vertex_count, 1 << 15), size_t{0},
      [&](const tbb::blocked_range<size_t>& range, size_t bad) {
        for (size_t i = range.begin(); i < range.end(); ++i) {
          if (!is_finite(mesh->positions[i])) {
            bad_vertex[i] = 1;
            mesh->positions[i] = Vec3(0.0f);
            ++bad;
          }
        }
        return bad;
      },
      std::plus<size_t>());

  const size_t tri_count = mesh->triangle_count();
  const bool has_normals = mesh->corner_normals.size() == tri_count * 3;
  const bool has_uvs = mesh->corner_uvs.size() == tri_count * 3;
  const bool has_slots = mesh->material_slots.size() == tri_count;
  // Attributes that do not hold three corners per triangle cannot be read safely: dropped.
  mesh->attributes.erase(std::remove_if(mesh->attributes.begin(), mesh->attributes.end(),
                                        [&](const MeshAttribute& a) {
                                          return a.components < 1 || a.components > 4 ||
                                                 a.values.size() != tri_count * 3 * a.components;
                                        }),
                         mesh->attributes.end());
  if (!has_normals) mesh->corner_normals.clear();
  if (!has_uvs) mesh->corner_uvs.clear();
  if (!has_slots) mesh->material_slots.clear();
  mesh->indices.resize(tri_count * 3);

  std::vector<uint8_t> keep(tri_count, 0);
  const size_t dropped = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, tri_count, 1 << 14), size_t{0},
      [&](const tbb::blocked_range<size_t>& range, size_t dropped_here) {
        for (size_t t = range.begin(); t < range.end(); ++t) {
          const uint32_t i0 = mesh->indices[3 * t], i1 = mesh->indices[3 * t + 1],
                         i2 = mesh->indices[3 * t + 2];
          bool ok = i0 < vertex_count && i1 < vertex_count && i2 < vertex_count;
          ok = ok && !bad_vertex[i0] && !bad_vertex[i1] && !bad_vertex[i2];
          ok = ok && i0 != i1 && i1 != i2 && i0 != i2;
          if (ok) {
            const Vec3 &p0 = mesh->positions[i0], &p1 = mesh->positions[i1],
                       &p2 = mesh->positions[i2];
            const Vec3 e1 = p1 - p0, e2 = p2 - p0;
            const float area2 = length(cross(e1, e2));
            // Relative test: an area that vanishes next to the edge lengths is a sliver or a
            // point.
            const float scale = std::max(length_squared(e1), length_squared(e2));
            ok = std::isfinite(area2) && area2 > 1e-12f * scale && area2 > 0.0f;
          }
          if (!ok) {
            ++dropped_here;
            continue;
          }
          keep[t] = 1;
          for (size_t c = 3 * t; c < 3 * t + 3; ++c) {
            if (has_normals) {
              const Vec3 n = mesh->corner_normals[c];
              mesh->corner_normals[c] = is_finite(n) && length_squared(n) > 0 ? n : Vec3(0.0f);
            }
            if (has_uvs) {
              const Vec2 uv = mesh->corner_uvs[c];
              mesh->corner_uvs[c] =
                  std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : Vec2(0.0f, 0.0f);
            }
          }
        }
        return dropped_here;
      },
      std::plus<size_t>());
  report.dropped_triangles = dropped;

  size_t kept = tri_count;
  std::vector<uint32_t> source;
  if (dropped) {
    kept = 0;
    source.reserve(tri_count - dropped);
    for (size_t t = 0; t < tri_count; ++t) {
      if (!keep[t]) continue;
      for (int c = 0; c < 3; ++c) {
        mesh->indices[3 * kept + c] = mesh->indices[3 * t + c];
        if (has_normals) mesh->corner_normals[3 * kept + c] = mesh->corner_normals[3 * t + c];
        if (has_uvs) mesh->corner_uvs[3 * kept + c] = mesh->corner_uvs[3 * t + c];
      }
      if (has_slots) mesh->material_slots[kept] = mesh->material_slots[t];
      for (MeshAttribute& a : mesh->attributes) {
        const size_t n = 3 * a.components;
        std::copy_n(a.values.begin() + t * n, n, a.values.begin() + kept * n);
      }
      source.push_back(static_cast<uint32_t>(t));
      ++kept;
    }
  }
  mesh->indices.resize(kept * 3);
  if (has_normals) mesh->corner_normals.resize(kept * 3);
  if (has_uvs) mesh->corner_uvs.resize(kept * 3);
  if (has_slots) mesh->material_slots.resize(kept);
  for (MeshAttribute& a : mesh->attributes) a.values.resize(kept * 3 * a.components);
  // Composes with an earlier cleanup's numbering, so cleaning twice keeps the caller's indices.
  const bool had_source = mesh->source_triangles.size() == tri_count;
  if (!had_source) mesh->source_triangles.clear();
  if (kept != tri_count) {
    if (had_source)
      for (uint32_t& s : source) s = mesh->source_triangles[s];
    mesh->source_triangles = std::move(source);
  }
  return report;
}

}  // namespace photon

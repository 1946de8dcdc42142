#include "photon/scene/mesh_import.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace photon {

void gather_loop_mesh(const LoopMeshView& view, Mesh* mesh) {
  const size_t corners = view.corner_count - view.corner_count % 3;
  const size_t vertex_count = mesh->positions.size();
  constexpr uint32_t kInvalid = UINT32_MAX;
  mesh->indices.resize(corners);
  if (view.vertex_normals || view.loop_normals) mesh->corner_normals.resize(corners);
  if (view.loop_uvs) mesh->corner_uvs.resize(corners);

  // Corners are independent: gathered in parallel (a 1M-triangle mesh has 3M corners whose
  // scattered reads dominate the import).
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, corners, 1 << 14),
      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t k = range.begin(); k < range.end(); ++k) {
          const int32_t loop = view.corner_loops[k];
          const bool loop_ok = loop >= 0 && static_cast<size_t>(loop) < view.loop_count;
          const int32_t vertex = loop_ok ? view.loop_vertices[loop] : -1;
          const bool vertex_ok = vertex >= 0 && static_cast<size_t>(vertex) < vertex_count;
          mesh->indices[k] = vertex_ok ? static_cast<uint32_t>(vertex) : kInvalid;
          if (view.loop_normals) {
            const float* n = loop_ok ? view.loop_normals + 3 * static_cast<size_t>(loop) : nullptr;
            mesh->corner_normals[k] = n ? Vec3(n[0], n[1], n[2]) : Vec3(0.0f);
          } else if (view.vertex_normals) {
            const float* n =
                vertex_ok ? view.vertex_normals + 3 * static_cast<size_t>(vertex) : nullptr;
            mesh->corner_normals[k] = n ? Vec3(n[0], n[1], n[2]) : Vec3(0.0f);
          }
          if (view.loop_uvs) {
            const float* uv = loop_ok ? view.loop_uvs + 2 * static_cast<size_t>(loop) : nullptr;
            mesh->corner_uvs[k] = uv ? Vec2(uv[0], uv[1]) : Vec2(0.0f, 0.0f);
          }
        }
      });
}

void snap_normals(Mesh* mesh) {
  constexpr float kScale = 65536.0f, kInv = 1.0f / 65536.0f;
  std::vector<Vec3>& normals = mesh->corner_normals;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, normals.size(), 1 << 15),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i < range.end(); ++i) {
                        Vec3& n = normals[i];
                        n.x = std::nearbyint(n.x * kScale) * kInv;
                        n.y = std::nearbyint(n.y * kScale) * kInv;
                        n.z = std::nearbyint(n.z * kScale) * kInv;
                      }
                    });
}

}  // namespace photon

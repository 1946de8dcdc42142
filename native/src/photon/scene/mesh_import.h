// Builds a Mesh from polygon-mesh data laid out as Blender stores it: per-vertex positions,
// per-loop (face corner) attributes, and three loop indices per triangle. Gathering per-corner
// arrays here is several times faster than fancy indexing in numpy on the Python side.
#pragma once

#include <cstddef>
#include <cstdint>

#include "photon/scene/scene.h"

namespace photon {

struct LoopMeshView {
  const int32_t* corner_loops = nullptr;  // 3 per triangle: loop index of each corner
  size_t corner_count = 0;
  const int32_t* loop_vertices = nullptr;  // vertex index of each loop
  size_t loop_count = 0;
  const float* vertex_normals = nullptr;  // 3 per vertex (smooth shading), or null
  const float* loop_normals = nullptr;    // 3 per loop (split/custom normals), or null
  const float* loop_uvs = nullptr;        // 2 per loop, or null
};

// Fills mesh->indices and, when the view has them, mesh->corner_normals / corner_uvs.
// mesh->positions must be set. Out-of-range loop or vertex indices become invalid triangle
// indices, which clean_mesh() drops.
void gather_loop_mesh(const LoopMeshView& view, Mesh* mesh);

// Rounds corner normals to multiples of 2^-16 (1.5e-5 is far finer than shading needs), so
// normals that differ only in their last bits become identical, but for a tie at a rounding
// boundary. Vertex normals, which Blender 3.4 sums across threads in no fixed order, are no
// longer read from it (vertex_normals.h computes them); this still evens out normals handed in
// by other callers.
void snap_normals(Mesh* mesh);

}  // namespace photon

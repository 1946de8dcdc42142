// Smooth-shading vertex normals of a polygon mesh, computed the way Blender defines them but in
// a fixed order. Blender 3.4 accumulates each vertex's normal from its faces on several threads
// with atomic adds, so the same mesh can arrive with normals that differ in the last bits from
// one run to the next; computed here, equal input gives equal normals, whatever the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "photon/base/math.h"

namespace photon {

struct PolygonMeshView {
  const Vec3* positions = nullptr;
  size_t vertex_count = 0;
  const int32_t* loop_vertices = nullptr;  // vertex index of each loop (face corner)
  size_t loop_count = 0;
  const int32_t* poly_loop_starts = nullptr;  // first loop of each polygon
  const int32_t* poly_loop_totals = nullptr;  // its number of loops
  size_t poly_count = 0;
};

// The normal of each vertex: the sum over the polygons around it of the polygon's normal
// weighted by the polygon's angle at that vertex (Thürmer and Wüthrich, "Computing vertex
// normals from polygonal facets", JGT 1998), normalized. A vertex no polygon weighs on gets its
// position's direction, as in Blender (zero if that is not finite). Polygons reaching outside
// the arrays, or with a degenerate or non-finite normal, are skipped.
std::vector<Vec3> angle_weighted_vertex_normals(const PolygonMeshView& mesh);

// Per-loop normals of a mesh mixing smooth and flat polygons (Blender without Auto Smooth or
// custom normals): a smooth polygon's loops take their vertex's normal (`vertex_normals`, from
// every polygon around it, flat ones too), a flat polygon's loops its own normal. Loops outside
// every valid polygon get zero (no shading normal).
std::vector<Vec3> smooth_and_flat_loop_normals(const PolygonMeshView& mesh,
                                               const uint8_t* poly_smooth,
                                               const std::vector<Vec3>& vertex_normals);

// A polygon's unit normal as Blender computes it: the cross product of the edges for a
// triangle, of the diagonals for a quad, Newell's method beyond; zero when degenerate (such a
// polygon weighs on no vertex).
Vec3 polygon_normal(const Vec3* positions, const int32_t* loop_vertices, size_t corners);

}  // namespace photon

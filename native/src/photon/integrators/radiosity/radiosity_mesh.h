// The elements (patches) of the radiosity solution: every diffuse triangle of every instance,
// in world space, split by a regular barycentric subdivision into n x n congruent sub-triangles
// (n from the target patch size), so the element under an Embree hit follows from its (u, v)
// without a search. Each element has two sides (Blender faces are two-sided), each with its own
// radiosity. Element corners are welded into shared vertices within an instance (same position,
// agreeing normals), and vertex radiosity is the area-weighted average of the elements around
// it, so interpolating it across an element (Gouraud) hides the patch edges.
//
// Patches (the unknowns of the solve) are built from elements adaptively (Cohen & Wallace 1993,
// ch. 8, on meshing to a target element size; Bekaert 1999, ch. 6, on clustering for
// stochastic radiosity): a triangle larger than the patch size is subdivided and each of its
// elements is a patch; triangles much smaller than the patch size keep one element each but
// are clustered, by world-space voxel of the patch size and by the dominant axis of their
// normal, into one patch per voxel, so a finely tessellated mesh does not turn into millions of
// patches that each receive a handful of rays. The automatic patch size aims at a patch count
// that is bounded by the solve's ray budget (enough rays per patch for a target noise).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "photon/render/accel.h"

namespace photon {

struct RadiosityTriangle {
  Vec3 p0, e1, e2;            // world space: p = p0 + b1 e1 + b2 e2 (Embree's u = b1, v = b2)
  Vec3 normal;                // unit, as wound
  float element_area = 0.0f;  // area / n^2, the finest element's
  // Lattice subdivisions per edge (the patch-size subdivision times 2^levels); 0 = not meshed
  // (not diffuse).
  uint32_t n = 0;
  uint32_t first_element = 0;
  uint32_t first_lattice = 0;        // (n + 1)(n + 2) / 2 lattice points
  uint32_t first_cell = UINT32_MAX;  // refined: element of each of the n^2 lattice cells
  uint8_t levels = 0;                // local refinement levels of its instance
  bool clustered = false;            // n = 1 and its element is part of a cluster patch
};

// An element's place in its triangle: cell (i, j) of the subdivision at its level (n >> (levels
// - level) per edge), upward (corners (i,j), (i+1,j), (i,j+1)) or downward (corners
// (i+1,j+1), (i,j+1), (i+1,j)).
struct RadiosityElement {
  uint32_t triangle = 0;
  uint16_t i = 0, j = 0;
  uint8_t level = 0;
  bool up = true;
};

// A cell of a triangle's refinement hierarchy: (i, j, up) on the patch-size subdivision refined
// `level` times (2^level times as many cells per edge).
struct RadiosityCell {
  uint32_t triangle = 0;
  uint16_t i = 0, j = 0;
  uint8_t level = 0;
  bool up = true;
  bool operator<(const RadiosityCell& o) const {
    if (triangle != o.triangle) return triangle < o.triangle;
    if (level != o.level) return level < o.level;
    if (i != o.i) return i < o.i;
    if (j != o.j) return j < o.j;
    return up < o.up;
  }
  bool operator==(const RadiosityCell& o) const {
    return triangle == o.triangle && level == o.level && i == o.i && j == o.j && up == o.up;
  }
};

// Where a surface point lies: its element, the element's three welded vertices with the side
// flip of each (a vertex welded from a triangle wound the other way swaps front and back), and
// the point's barycentric weights in the element.
struct RadiosityLocation {
  uint32_t element = 0;
  uint32_t vertex[3] = {0, 0, 0};
  bool flip[3] = {false, false, false};
  float weight[3] = {1.0f, 0.0f, 0.0f};
};

struct RadiosityMeshSettings {
  float patch_size = 0.0f;           // target element edge length; <= 0: automatic
  size_t auto_elements = 20000;      // automatic size: about this many patches
  size_t max_elements = 4000000;     // larger meshes are coarsened (with a warning)
  uint32_t max_subdivisions = 1024;  // per triangle edge
  // Ray budget of the solve (0 = unknown): the automatic size then also keeps the patch count
  // at or below rays / min_rays_per_patch. A patch hit by k rays per step has a relative noise
  // of about 1 / sqrt(k) (Bekaert 1999, sec. 6.3): 256 rays give about 6 %.
  uint64_t rays = 0;
  uint32_t min_rays_per_patch = 256;
  size_t min_patches = 64;  // the ray cap never goes below this
  // Triangles whose longest edge is below this fraction of the patch size are clustered.
  float cluster_fraction = 0.5f;
  // Local refinement (Cohen et al. 1986; Cohen & Wallace 1993, ch. 8): cells of subdivided
  // triangles to split into 2 x 2 (a split cell's children may be split in turn). Each element
  // is a leaf cell and a patch; the lattice of a refined instance is that of its finest level,
  // so the corners of all elements are welded lattice points (T-vertices included).
  const std::vector<RadiosityCell>* split_cells = nullptr;
  uint32_t max_levels = 4;
};

class RadiosityMesh {
 public:
  RadiosityMesh() = default;
  // `meshed(material)`: whether triangles of this material get elements (diffuse surfaces);
  // the others (mirrors, glass) only redirect rays. Warnings are appended to `warnings`.
  RadiosityMesh(const Scene& scene, const Accel& accel, const RadiosityMeshSettings& settings,
                const std::function<bool(const Material&)>& meshed,
                std::vector<std::string>* warnings);

  size_t element_count() const { return elements_.size(); }
  size_t patch_count() const { return patch_area_.size(); }
  size_t cluster_count() const { return cluster_count_; }
  size_t split_count() const { return split_count_; }  // cells split by local refinement
  size_t vertex_count() const { return vertex_count_; }
  size_t triangle_count() const { return triangles_.size(); }
  float patch_size() const { return patch_size_; }
  double total_area() const { return total_area_; }

  const RadiosityElement& element(uint32_t e) const { return elements_[e]; }
  const RadiosityTriangle& triangle_of(uint32_t e) const {
    return triangles_[elements_[e].triangle];
  }
  // Doublings from element e's grid to its triangle's lattice (0 unless locally refined).
  uint32_t element_shift(uint32_t e) const { return triangle_of(e).levels - elements_[e].level; }
  float area(uint32_t e) const {
    return triangle_of(e).element_area * static_cast<float>(1u << (2 * element_shift(e)));
  }
  // The cell of a patch that is one element of a subdivided triangle (see patch_clustered).
  RadiosityCell patch_cell(uint32_t p) const {
    const RadiosityElement& el = elements_[patch_elements_[patch_first_[p]]];
    return {el.triangle, el.i, el.j, el.level, el.up};
  }
  Vec3 normal(uint32_t e) const { return triangle_of(e).normal; }
  // World-space corner k (0..2) of element e, and a uniform point on it.
  Vec3 corner(uint32_t e, int k) const;
  Vec3 sample_point(uint32_t e, Vec2 u) const;

  // The patch element e belongs to. Every element of a patch has its normal within 55 degrees
  // of the patch's axis, so an element's front side is its patch's front side.
  uint32_t patch_of(uint32_t e) const { return element_patch_[e]; }
  float patch_area(uint32_t p) const { return patch_area_[p]; }
  Vec3 patch_centroid(uint32_t p) const { return patch_centroid_[p]; }
  Vec3 patch_normal(uint32_t p) const { return patch_normal_[p]; }  // area-weighted, unit
  uint32_t patch_instance(uint32_t p) const { return patch_instance_[p]; }
  bool patch_clustered(uint32_t p) const {
    return triangle_of(patch_elements_[patch_first_[p]]).clustered;
  }
  uint32_t patch_element_count(uint32_t p) const { return patch_first_[p + 1] - patch_first_[p]; }
  // A uniform point on patch p: an element chosen with probability proportional to its area
  // (by `u_element`), then a uniform point on it. `element` receives the element.
  Vec3 sample_patch(uint32_t p, float u_element, Vec2 u, uint32_t* element) const;

  // The element hit by Embree at (instance, primitive, u, v); false for unmeshed triangles.
  bool locate(uint32_t instance, uint32_t primitive, float u, float v,
              RadiosityLocation* out) const;
  // The three welded vertices of element e (and their side flips).
  void element_vertices(uint32_t e, uint32_t vertex[3], bool flip[3]) const;
  // The welded lattice vertices along edge k of element e (corner k to corner k + 1), ends
  // included: 2^element_shift(e) + 1 of them; the inner ones are T-vertices where smaller
  // elements meet the edge. `flip` as in element_vertices.
  void edge_vertices(uint32_t e, int k, std::vector<uint32_t>* vertex,
                     std::vector<uint8_t>* flip) const;

 private:
  uint32_t triangle_index(uint32_t instance, uint32_t primitive) const;
  uint32_t lattice_vertex(const RadiosityTriangle& t, uint32_t a, uint32_t b, bool* flip) const;

  std::vector<RadiosityTriangle> triangles_;
  std::vector<uint32_t> instance_first_triangle_;  // by Embree instance id
  std::vector<RadiosityElement> elements_;
  std::vector<uint32_t> lattice_;       // welded vertex << 1 | flip, per lattice point
  std::vector<uint32_t> cell_element_;  // refined triangles: element of each lattice cell
  std::vector<uint32_t> element_patch_;
  std::vector<uint32_t> patch_first_;     // patch p owns patch_elements_[first[p], first[p+1])
  std::vector<uint32_t> patch_elements_;  // in element order within each patch
  std::vector<float> patch_cdf_;          // cumulative element area, per patch_elements_ entry
  std::vector<float> patch_area_;
  std::vector<Vec3> patch_centroid_, patch_normal_;
  std::vector<uint32_t> patch_instance_;
  size_t cluster_count_ = 0;
  size_t split_count_ = 0;
  size_t vertex_count_ = 0;
  float patch_size_ = 0.0f;
  double total_area_ = 0.0;
};

// Index of element (i, j, up) within a triangle subdivided n times (n^2 elements: the upward
// ones row by row, then the downward ones).
inline uint32_t subdivision_element(uint32_t n, uint32_t i, uint32_t j, bool up) {
  if (up) return i * n - i * (i - 1) / 2 + j;
  return n * (n + 1) / 2 + i * (n - 1) - i * (i - 1) / 2 + j;
}

// Index of lattice point (a, b), a + b <= n, within a triangle subdivided n times.
inline uint32_t subdivision_lattice(uint32_t n, uint32_t a, uint32_t b) {
  return a * (n + 1) - a * (a - 1) / 2 + b;
}

}  // namespace photon

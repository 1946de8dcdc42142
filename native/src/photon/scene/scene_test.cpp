#include "photon/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace photon {
namespace scene_test {
namespace {

// Tags every per-triangle attribute with the triangle's original index t, so we can tell
// which triangle a surviving attribute came from.
Vec3 normal_tag(size_t t, int c) {
  return Vec3(static_cast<float>(t + 1), static_cast<float>(c + 1), 1.0f);
}
Vec2 uv_tag(size_t t, int c) {
  return Vec2(static_cast<float>(t), static_cast<float>(c) * 0.25f);
}
int32_t slot_tag(size_t t) {
  return static_cast<int32_t>(10 * t + 3);
}

void tag_attributes(Mesh* mesh) {
  mesh->corner_normals.clear();
  mesh->corner_uvs.clear();
  mesh->material_slots.clear();
  for (size_t t = 0; t < mesh->triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      mesh->corner_normals.push_back(normal_tag(t, c));
      mesh->corner_uvs.push_back(uv_tag(t, c));
    }
    mesh->material_slots.push_back(slot_tag(t));
  }
}

// Checks that `mesh` holds exactly the original triangles `kept`, in order, with their attributes.
void expect_kept(const Mesh& mesh, const std::vector<uint32_t>& original_indices,
                 const std::vector<size_t>& kept) {
  ASSERT_EQ(mesh.triangle_count(), kept.size());
  ASSERT_EQ(mesh.indices.size(), 3 * kept.size());
  ASSERT_EQ(mesh.corner_normals.size(), 3 * kept.size());
  ASSERT_EQ(mesh.corner_uvs.size(), 3 * kept.size());
  ASSERT_EQ(mesh.material_slots.size(), kept.size());
  for (size_t k = 0; k < kept.size(); ++k) {
    const size_t t = kept[k];
    SCOPED_TRACE(::testing::Message() << "kept triangle " << k << " (originally " << t << ")");
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(mesh.indices[3 * k + c], original_indices[3 * t + c]);
      const Vec3 n = mesh.corner_normals[3 * k + c], en = normal_tag(t, c);
      EXPECT_EQ(n.x, en.x);
      EXPECT_EQ(n.y, en.y);
      EXPECT_EQ(n.z, en.z);
      EXPECT_EQ(mesh.corner_uvs[3 * k + c].x, uv_tag(t, c).x);
      EXPECT_EQ(mesh.corner_uvs[3 * k + c].y, uv_tag(t, c).y);
    }
    EXPECT_EQ(mesh.material_slots[k], slot_tag(t));
  }
}

TEST(CleanMesh, DropsUnrenderableTrianglesAndKeepsAttributesAligned) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Mesh mesh;
  mesh.positions = {
      {0, 0, 0},    // 0
      {1, 0, 0},    // 1
      {0, 1, 0},    // 2
      {2, 0, 0},    // 3: on the line through 0 and 1
      {0, 0, 1},    // 4
      {1, 1, 1},    // 5
      {nan, 0, 0},  // 6
      {0, 0, 0},    // 7: same place as 0
      {0, inf, 0},  // 8
  };
  mesh.indices = {
      0, 1,  2,   // 0 keep
      0, 1,  6,   // 1 NaN vertex
      0, 0,  1,   // 2 repeated index
      4, 5,  1,   // 3 keep
      0, 1,  99,  // 4 index out of range
      0, 1,  3,   // 5 collinear: zero area
      2, 0,  7,   // 6 two corners at the same place: zero area
      5, 8,  4,   // 7 infinite vertex
      1, 2,  2,   // 8 repeated index
      2, 5,  4,   // 9 keep
      9, 10, 11,  // 10 all out of range
  };
  tag_attributes(&mesh);
  const std::vector<uint32_t> original = mesh.indices;

  const MeshCleanupReport report = clean_mesh(&mesh);
  EXPECT_EQ(report.non_finite_vertices, 2u);
  EXPECT_EQ(report.dropped_triangles, 8u);
  expect_kept(mesh, original, {0, 3, 9});
  // Vertices are not removed (indices stay valid) but the bad ones are made finite.
  ASSERT_EQ(mesh.positions.size(), 9u);
  for (const Vec3& p : mesh.positions) EXPECT_TRUE(is_finite(p));
  EXPECT_EQ(mesh.positions[5].x, 1.0f);  // good vertices are untouched
}

TEST(CleanMesh, CleanMeshIsUntouched) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  tag_attributes(&mesh);
  const std::vector<uint32_t> original = mesh.indices;
  const MeshCleanupReport report = clean_mesh(&mesh);
  EXPECT_EQ(report.non_finite_vertices, 0u);
  EXPECT_EQ(report.dropped_triangles, 0u);
  expect_kept(mesh, original, {0, 1});
}

TEST(CleanMesh, AreaTestIsRelativeToTheTriangleSize) {
  // A tiny but well-shaped triangle is real geometry (e.g. a model in millimetres scaled down);
  // a needle whose area vanishes next to its edges is not.
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1e-4f, 0, 0}, {0, 1e-4f, 0},      // tiny right triangle
                    {0, 0, 0}, {1000, 0, 0},  {2000, 1e-9f, 0}};  // needle, height 1e-9 at 2000
  mesh.indices = {0, 1, 2, 3, 4, 5};
  tag_attributes(&mesh);
  const std::vector<uint32_t> original = mesh.indices;
  const MeshCleanupReport report = clean_mesh(&mesh);
  EXPECT_EQ(report.dropped_triangles, 1u);
  expect_kept(mesh, original, {0});
}

TEST(CleanMesh, ResetsNonFiniteNormalsAndUvsOfKeptTriangles) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2};
  mesh.corner_normals = {{0, 0, 1}, {nan, 0, 1}, {0, 0, 0}};
  mesh.corner_uvs = {{0.5f, 0.5f}, {nan, 0.0f}, {0.0f, INFINITY}};
  const MeshCleanupReport report = clean_mesh(&mesh);
  EXPECT_EQ(report.dropped_triangles, 0u);
  ASSERT_EQ(mesh.corner_normals.size(), 3u);
  EXPECT_EQ(mesh.corner_normals[0].z, 1.0f);
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(is_finite(mesh.corner_normals[c]));
  ASSERT_EQ(mesh.corner_uvs.size(), 3u);
  EXPECT_EQ(mesh.corner_uvs[0].x, 0.5f);
  for (const Vec2& uv : mesh.corner_uvs) {
    EXPECT_TRUE(std::isfinite(uv.x));
    EXPECT_TRUE(std::isfinite(uv.y));
  }
}

TEST(CleanMesh, DropsMismatchedAttributeArraysAndATrailingPartialTriangle) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  mesh.indices = {0, 1, 2, 1, 3, 2, 0, 1};  // two triangles and two stray indices
  mesh.corner_normals = {{0, 0, 1}};        // wrong length: cannot be aligned, so dropped
  mesh.corner_uvs.assign(6, Vec2(0.25f, 0.75f));
  mesh.material_slots = {1, 2, 3};  // wrong length
  const MeshCleanupReport report = clean_mesh(&mesh);
  EXPECT_EQ(report.dropped_triangles, 0u);
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.indices.size(), 6u);
  EXPECT_TRUE(mesh.corner_normals.empty());
  EXPECT_EQ(mesh.corner_uvs.size(), 6u);
  EXPECT_TRUE(mesh.material_slots.empty());
}

TEST(CleanMesh, EverythingDroppedLeavesAnEmptyMesh) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Mesh mesh;
  mesh.positions = {{nan, nan, nan}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2, 1, 1, 2, 5, 1, 2};
  tag_attributes(&mesh);
  const MeshCleanupReport report = clean_mesh(&mesh);
  EXPECT_EQ(report.non_finite_vertices, 1u);
  EXPECT_EQ(report.dropped_triangles, 3u);
  EXPECT_EQ(mesh.triangle_count(), 0u);
  EXPECT_TRUE(mesh.corner_normals.empty());
  EXPECT_TRUE(mesh.corner_uvs.empty());
  EXPECT_TRUE(mesh.material_slots.empty());
}

TEST(Scene, DefaultMaterialIsAGreyDiffuse) {
  const Material& m = Scene::default_material();
  EXPECT_EQ(&m, &Scene::default_material());
  ASSERT_EQ(m.closures.size(), 1u);
  EXPECT_EQ(m.closures[0].type, ClosureType::kDiffuse);
  EXPECT_FALSE(m.may_emit());
  const Vec3 c = m.closures[0][Param::kColor].value;
  EXPECT_GT(c.x, 0.0f);
  EXPECT_EQ(c.x, c.y);
  EXPECT_EQ(c.y, c.z);
}

}  // namespace
}  // namespace scene_test
}  // namespace photon

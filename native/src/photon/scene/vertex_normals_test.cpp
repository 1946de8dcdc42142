#include "photon/scene/vertex_normals.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace photon {
namespace vertex_normals_test {
namespace {

struct PolygonMesh {
  std::vector<Vec3> positions;
  std::vector<int32_t> loop_vertices, starts, totals;

  void add_polygon(std::initializer_list<int32_t> verts) {
    starts.push_back(static_cast<int32_t>(loop_vertices.size()));
    totals.push_back(static_cast<int32_t>(verts.size()));
    loop_vertices.insert(loop_vertices.end(), verts);
  }
  PolygonMeshView view() const {
    return {positions.data(), positions.size(), loop_vertices.data(), loop_vertices.size(),
            starts.data(),    totals.data(),    starts.size()};
  }
};

// A UV sphere of quads with triangle fans at the poles, as Blender's primitive.
PolygonMesh uv_sphere(int segments, int rings) {
  const float pi = 3.14159265f;
  PolygonMesh m;
  m.positions.push_back(Vec3(0, 0, 1));
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const float theta = pi * r / rings, phi = 2 * pi * s / segments;
      m.positions.push_back(
          Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  m.positions.push_back(Vec3(0, 0, -1));
  const int south = static_cast<int>(m.positions.size()) - 1;
  const auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    m.add_polygon({0, ring(1, s), ring(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r)
      m.add_polygon({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)});
    m.add_polygon({ring(rings - 1, s), south, ring(rings - 1, s + 1)});
  }
  return m;
}

TEST(VertexNormals, CubeCornersPointAlongTheDiagonals) {
  PolygonMesh cube;
  for (int i = 0; i < 8; ++i)
    cube.positions.push_back(Vec3(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f));
  cube.add_polygon({0, 2, 3, 1});  // -z
  cube.add_polygon({4, 5, 7, 6});  // +z
  cube.add_polygon({0, 1, 5, 4});  // -y
  cube.add_polygon({2, 6, 7, 3});  // +y
  cube.add_polygon({0, 4, 6, 2});  // -x
  cube.add_polygon({1, 3, 7, 5});  // +x
  const std::vector<Vec3> n = angle_weighted_vertex_normals(cube.view());
  for (int i = 0; i < 8; ++i) {
    const Vec3 expected = normalize(cube.positions[i]);
    EXPECT_NEAR(n[i].x, expected.x, 1e-6f) << i;
    EXPECT_NEAR(n[i].y, expected.y, 1e-6f) << i;
    EXPECT_NEAR(n[i].z, expected.z, 1e-6f) << i;
  }
}

TEST(VertexNormals, AngleWeightsMakeTheNormalIndependentOfHowAFaceIsSplit) {
  // A corner of a cube whose top face is split into two triangles at one vertex: area or
  // count weights would lean that vertex's normal toward +z, angle weights do not.
  PolygonMesh m;
  m.positions = {Vec3(0, 0, 0),  Vec3(1, 0, 0),  Vec3(1, 1, 0), Vec3(0, 1, 0),
                 Vec3(0, 0, -1), Vec3(1, 0, -1), Vec3(0, 1, -1)};
  m.add_polygon({0, 1, 2});     // top, first half (+z)
  m.add_polygon({0, 2, 3});     // top, second half
  m.add_polygon({0, 4, 5, 1});  // front (-y)
  m.add_polygon({0, 3, 6, 4});  // left (-x)
  const Vec3 n = angle_weighted_vertex_normals(m.view())[0];
  EXPECT_NEAR(n.x, -1 / std::sqrt(3.f), 1e-6f);
  EXPECT_NEAR(n.y, -1 / std::sqrt(3.f), 1e-6f);
  EXPECT_NEAR(n.z, 1 / std::sqrt(3.f), 1e-6f);
}

TEST(VertexNormals, SphereNormalsPointOutward) {
  const PolygonMesh sphere = uv_sphere(32, 16);
  const std::vector<Vec3> n = angle_weighted_vertex_normals(sphere.view());
  ASSERT_EQ(n.size(), sphere.positions.size());
  for (size_t i = 0; i < n.size(); ++i) {
    EXPECT_NEAR(length(n[i]), 1.0f, 1e-6f);
    EXPECT_GT(dot(n[i], sphere.positions[i]), 0.9999f) << i;
  }
}

TEST(VertexNormals, NgonsUseNewellsNormal) {
  PolygonMesh hexagon;
  for (int i = 0; i < 6; ++i)
    hexagon.positions.push_back(Vec3(std::cos(i * 1.0472f), std::sin(i * 1.0472f), 0.5f));
  hexagon.add_polygon({0, 1, 2, 3, 4, 5});
  for (const Vec3& n : angle_weighted_vertex_normals(hexagon.view())) {
    EXPECT_NEAR(n.z, 1.0f, 1e-6f);
  }
  const int32_t reversed[] = {5, 4, 3, 2, 1, 0};
  EXPECT_NEAR(polygon_normal(hexagon.positions.data(), reversed, 6).z, -1.0f, 1e-6f);
}

TEST(VertexNormals, SameBitsWhateverTheThreadCount) {
  const PolygonMesh sphere = uv_sphere(400, 200);  // 80k polygons: several parallel chunks
  std::vector<Vec3> one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = angle_weighted_vertex_normals(sphere.view());
  }
  many = angle_weighted_vertex_normals(sphere.view());
  ASSERT_EQ(one.size(), many.size());
  EXPECT_EQ(0, std::memcmp(one.data(), many.data(), one.size() * sizeof(Vec3)));
}

TEST(VertexNormals, BadPolygonsAreSkippedAndLooseVerticesPointAwayFromTheOrigin) {
  PolygonMesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                 Vec3(0, 0, 5), Vec3(2, 2, 2), Vec3(nan, 0, 0)};
  m.add_polygon({0, 1, 2});
  m.add_polygon({0, 1, 99});                        // a vertex out of range
  m.add_polygon({0, 1});                            // fewer than three corners
  m.add_polygon({4, 4, 4});                         // no area: no normal to weigh
  m.starts.push_back(1000), m.totals.push_back(3);  // loops out of range
  m.add_polygon({0, 5, 1});                         // a NaN vertex
  const std::vector<Vec3> n = angle_weighted_vertex_normals(m.view());
  ASSERT_EQ(n.size(), 6u);
  EXPECT_NEAR(n[3].z, 1.0f, 1e-6f);                // loose: its position's direction
  EXPECT_NEAR(n[4].x, 1 / std::sqrt(3.f), 1e-6f);  // only on the degenerate one: loose
  EXPECT_NEAR(n[1].z, 1.0f, 1e-6f);                // only the good triangle weighs on these
  EXPECT_NEAR(n[2].z, 1.0f, 1e-6f);
}

TEST(VertexNormals, FlatPolygonsKeepTheirNormalAndStillBendTheirNeighbours) {
  PolygonMesh m;  // two faces meeting at a right angle along the edge 0-1
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0),  Vec3(1, 1, 0),
                 Vec3(0, 1, 0), Vec3(0, 0, -1), Vec3(1, 0, -1)};
  m.add_polygon({0, 1, 2, 3});  // top (+z), smooth
  m.add_polygon({0, 4, 5, 1});  // front (-y), flat
  const std::vector<Vec3> vertex = angle_weighted_vertex_normals(m.view());
  const uint8_t smooth[] = {1, 0};
  const std::vector<Vec3> loops = smooth_and_flat_loop_normals(m.view(), smooth, vertex);
  ASSERT_EQ(loops.size(), 8u);
  const float h = 1 / std::sqrt(2.f);
  EXPECT_NEAR(loops[0].y, -h, 1e-6f);  // the top's loop at vertex 0: bent by the front face
  EXPECT_NEAR(loops[0].z, h, 1e-6f);
  EXPECT_NEAR(loops[2].z, 1.0f, 1e-6f);  // vertex 2 touches the top only
  for (int l = 4; l < 8; ++l) EXPECT_NEAR(loops[l].y, -1.0f, 1e-6f) << l;
}

TEST(VertexNormals, RandomBrokenPolygonArraysNeverReachOutside) {
  // Loop starts and counts anywhere (negative, past the end, overflowing int32 when added),
  // vertex indices out of range, NaN and infinite positions: the arrays are only read inside
  // their bounds (the sanitizer build checks), and every normal is unit length or zero.
  std::mt19937 rng(7);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (int round = 0; round < 200; ++round) {
    PolygonMesh m;
    const int vertices = 1 + static_cast<int>(rng() % 20);
    for (int v = 0; v < vertices; ++v) {
      const uint32_t pick = rng() % 20;
      const float special = pick == 0 ? nan : pick == 1 ? inf : pick == 2 ? 0.0f : 1.0f;
      m.positions.push_back(Vec3(std::uniform_real_distribution<float>(-1, 1)(rng) * special,
                                 std::uniform_real_distribution<float>(-1, 1)(rng),
                                 std::uniform_real_distribution<float>(-1, 1)(rng)));
    }
    const int loops = static_cast<int>(rng() % 40);
    for (int l = 0; l < loops; ++l)
      m.loop_vertices.push_back(static_cast<int32_t>(rng() % (vertices + 3)) - 1);
    const int polys = static_cast<int>(rng() % 12);
    for (int p = 0; p < polys; ++p) {
      const uint32_t pick = rng() % 10;
      m.starts.push_back(pick == 0   ? -5
                         : pick == 1 ? std::numeric_limits<int32_t>::max()
                                     : static_cast<int32_t>(rng() % (loops + 2)));
      m.totals.push_back(pick == 2 ? std::numeric_limits<int32_t>::max()
                                   : static_cast<int32_t>(rng() % 7) - 1);
    }
    const std::vector<Vec3> normals = angle_weighted_vertex_normals(m.view());
    std::vector<uint8_t> smooth(m.starts.size());
    for (uint8_t& f : smooth) f = rng() % 2;
    const std::vector<Vec3> loop_normals =
        smooth_and_flat_loop_normals(m.view(), smooth.data(), normals);
    ASSERT_EQ(loop_normals.size(), m.loop_vertices.size());
    for (const Vec3& n : loop_normals) {
      const float l = length(n);
      EXPECT_TRUE(l == 0.0f || std::fabs(l - 1.0f) < 1e-5f) << l;
    }
  }
}

}  // namespace
}  // namespace vertex_normals_test
}  // namespace photon

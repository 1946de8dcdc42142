#include "photon/integrators/radiosity/radiosity_mesh.h"

#include <gtest/gtest.h>

#include "photon/base/rng.h"
#include "photon/integrators/radiosity/radiosity_field.h"
#include "photon/testing/radiosity_test_util.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/test_util.h"

namespace photon {
namespace radiosity_mesh_test {
namespace {

Scene single(Mesh mesh) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, std::move(mesh), 0);
  return scene;
}

TEST(RadiosityMesh, ElementsTileEveryTriangle) {
  // A 2 x 1 quad (two triangles, longest edge sqrt(5)) and a tilted triangle.
  Scene scene = single(make_quad({0, 0, 0}, {2, 0, 0}, {0, 1, 0}));
  Mesh tri;
  tri.positions = {{0, 0, 1}, {0.7f, 0.1f, 1.3f}, {0.2f, 0.9f, 1.1f}};
  tri.indices = {0, 1, 2};
  add_mesh_instance(&scene, tri, 0);
  RadiosityFixture f(std::move(scene));
  const float size = 0.3f;
  const RadiosityMesh mesh = f.mesh(size);

  size_t expected = 0;
  // Per triangle: n = ceil(longest edge / size), n^2 elements whose areas add up to its area.
  std::vector<double> area_by_triangle(mesh.triangle_count(), 0.0);
  for (uint32_t e = 0; e < mesh.element_count(); ++e) {
    const Vec3 c0 = mesh.corner(e, 0), c1 = mesh.corner(e, 1), c2 = mesh.corner(e, 2);
    const float a = 0.5f * length(cross(c1 - c0, c2 - c0));
    EXPECT_NEAR(a, mesh.area(e), 1e-5f);
    area_by_triangle[mesh.element(e).triangle] += a;
  }
  const float longest[3] = {std::sqrt(5.0f), std::sqrt(5.0f),
                            length(Vec3(0.7f, 0.1f, 0.3f) - Vec3(0.2f, 0.9f, 0.1f))};
  const float areas[3] = {1.0f, 1.0f,
                          0.5f * length(cross(Vec3(0.7f, 0.1f, 0.3f), Vec3(0.2f, 0.9f, 0.1f)))};
  for (int t = 0; t < 3; ++t) {
    const uint32_t n = static_cast<uint32_t>(std::ceil(longest[t] / size));
    expected += n * n;
    EXPECT_NEAR(area_by_triangle[t], areas[t], 1e-4) << "triangle " << t;
  }
  EXPECT_EQ(mesh.element_count(), expected);
  EXPECT_NEAR(mesh.total_area(), 2.0 + areas[2], 1e-4);
}

TEST(RadiosityMesh, AutomaticSizeGivesAboutTheTargetCount) {
  RadiosityFixture f(make_cornell_box());
  const RadiosityMesh mesh = f.mesh(0.0f);
  EXPECT_LE(mesh.element_count(), RadiosityMeshSettings{}.auto_elements);
  EXPECT_GE(mesh.element_count(), RadiosityMeshSettings{}.auto_elements * 7 / 10);
  EXPECT_GT(mesh.patch_size(), 0.0f);
}

TEST(RadiosityMesh, LocateFindsTheElementAndWeightsThatRebuildThePoint) {
  RadiosityFixture f(single(make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0})));
  const RadiosityMesh mesh = f.mesh(0.13f);
  for (uint32_t k = 0; k < 2000; ++k) {
    Ray ray;
    ray.origin = Vec3(to_unit_float(mix64(2 * k)) * 1.98f - 0.99f,
                      to_unit_float(mix64(2 * k + 1)) * 1.98f - 0.99f, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    Hit hit;
    ASSERT_TRUE(f.accel.intersect(ray, kVisibleAll, &hit));
    RadiosityLocation where;
    ASSERT_TRUE(mesh.locate(hit.instance, hit.primitive, hit.u, hit.v, &where));
    Vec3 p(0.0f);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(where.weight[c], 0.0f);
      p += mesh.corner(where.element, c) * where.weight[c];
    }
    EXPECT_TRUE(VecNear(p, hit.p, 1e-4f)) << "sample " << k;
  }
}

TEST(RadiosityMesh, WeldsCoplanarTrianglesButNotCreases) {
  {  // A square: the two triangles share the diagonal, so (n + 1)^2 vertices.
    RadiosityFixture f(single(make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})));
    const RadiosityMesh mesh = f.mesh(0.1f);  // diagonal 1.414 -> n = 15
    EXPECT_EQ(mesh.vertex_count(), 16u * 16u);
  }
  {  // A cube: faces meet at 90 degrees and keep their own vertices.
    RadiosityFixture f(single(make_box({0, 0, 0}, {1, 1, 1})));
    const RadiosityMesh mesh = f.mesh(0.5f);  // n = 3
    EXPECT_EQ(mesh.vertex_count(), 6u * 4u * 4u);
  }
}

// Gouraud interpolation: with element values that jump from element to element, the displayed
// radiosity is still continuous across element edges and across the edge two triangles share.
TEST(RadiosityField, ContinuousAcrossTheSharedEdge) {
  RadiosityFixture f(single(make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0})));
  const RadiosityMesh mesh = f.mesh(0.2f);
  std::vector<RadiosityPower> power(2 * mesh.element_count());
  for (size_t s = 0; s < power.size(); ++s)
    power[s].indirect = Vec3(to_unit_float(mix64(s)), 0.5f, 1.0f) * mesh.area(uint32_t(s / 2));
  const RadiosityField field(mesh, power);

  auto value_at = [&](float x, float y, uint32_t* element) {
    Ray ray;
    ray.origin = Vec3(x, y, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    Hit hit;
    EXPECT_TRUE(f.accel.intersect(ray, kVisibleAll, &hit));
    RadiosityLocation where;
    EXPECT_TRUE(mesh.locate(hit.instance, hit.primitive, hit.u, hit.v, &where));
    *element = where.element;
    return field.radiosity_at(where, 0).indirect.x;
  };
  // The quad's diagonal runs from (-1, -1) to (1, 1); step across it at many places.
  float largest_jump = 0.0f, largest_element_difference = 0.0f;
  for (int k = 1; k < 40; ++k) {
    const float t = -1.0f + 2.0f * k / 40.0f + 0.013f;
    const float eps = 1e-4f;
    uint32_t e0, e1;
    const float a = value_at(t + eps, t - eps, &e0), b = value_at(t - eps, t + eps, &e1);
    ASSERT_NE(mesh.element(e0).triangle, mesh.element(e1).triangle);
    largest_jump = std::max(largest_jump, std::fabs(a - b));
    largest_element_difference =
        std::max(largest_element_difference, std::fabs(field.element_radiosity(e0, 0).indirect.x -
                                                       field.element_radiosity(e1, 0).indirect.x));
  }
  EXPECT_GT(largest_element_difference, 0.3f);  // piecewise constant display would jump
  EXPECT_LT(largest_jump, 0.01f);
}

}  // namespace
}  // namespace radiosity_mesh_test
}  // namespace photon

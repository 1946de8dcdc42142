// Adaptive patch sizing: large triangles are subdivided, tiny ones clustered, and the automatic
// patch count follows the ray budget (see radiosity_mesh.h).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>

#include "photon/base/rng.h"
#include "photon/integrators/radiosity/radiosity_field.h"
#include "photon/integrators/radiosity/radiosity_mesh.h"
#include "photon/integrators/radiosity/radiosity_solver.h"
#include "photon/testing/radiosity_test_util.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace radiosity_adaptive_test {
namespace {

// A 20 m floor of two triangles (instance 0) and a finely tessellated unit sphere above it
// (instance 1): a scene whose triangle sizes differ by orders of magnitude.
Scene floor_and_sphere(int segments) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 0);
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 1.5f}, 1.0f, segments, segments / 2), 0);
  return scene;
}

RadiosityMesh automatic_mesh(RadiosityFixture& f, uint64_t rays) {
  RadiosityMeshSettings ms;
  ms.rays = rays;
  return RadiosityMesh(f.scene, f.accel, ms, is_radiosity_surface, &f.warnings);
}

size_t floor_elements(const RadiosityMesh& mesh) {
  size_t count = 0;
  for (uint32_t e = 0; e < mesh.element_count(); ++e) count += mesh.element(e).triangle < 2;
  return count;
}

TEST(RadiosityAdaptive, HugeQuadBesideADenseMeshIsSubdivided) {
  RadiosityFixture f(floor_and_sphere(300));  // ~90k sphere triangles
  const RadiosityMesh mesh = automatic_mesh(f, 8000000);
  // One patch per sphere triangle (the old sizing) would leave the floor as 2 patches.
  EXPECT_GE(floor_elements(mesh), 2000u);
  EXPECT_LE(mesh.patch_count(), RadiosityMeshSettings{}.auto_elements);
  EXPECT_GE(mesh.patch_count(), RadiosityMeshSettings{}.auto_elements / 2);
  // The floor's patches are about as large as the sphere's (target area, not one per triangle).
  double floor_area = 0.0, sphere_area = 0.0;
  size_t floor_patches = 0, sphere_patches = 0;
  for (uint32_t p = 0; p < mesh.patch_count(); ++p) {
    const bool on_floor = mesh.patch_instance(p) == 0;
    (on_floor ? floor_area : sphere_area) += mesh.patch_area(p);
    ++(on_floor ? floor_patches : sphere_patches);
  }
  const double ratio = (floor_area / floor_patches) / (sphere_area / sphere_patches);
  EXPECT_GT(ratio, 0.25);
  EXPECT_LT(ratio, 4.0);
}

TEST(RadiosityAdaptive, ManyTinyTrianglesShareClusterPatches) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, make_uv_sphere({0, 0, 0}, 1.0f, 300, 150), 0);
  RadiosityFixture f(std::move(scene));
  const RadiosityMesh mesh = automatic_mesh(f, 1000000);
  const size_t triangles = mesh.triangle_count();
  ASSERT_GT(triangles, 80000u);
  EXPECT_LT(mesh.patch_count() * 20, triangles);
  EXPECT_GT(mesh.cluster_count(), 0u);
  // Every element faces its patch's way; patch areas add up; patch samples lie on the sphere.
  std::vector<double> area(mesh.patch_count(), 0.0);
  for (uint32_t e = 0; e < mesh.element_count(); ++e) {
    const uint32_t p = mesh.patch_of(e);
    ASSERT_LT(p, mesh.patch_count());
    EXPECT_GT(dot(mesh.normal(e), mesh.patch_normal(p)), 0.5f) << "element " << e;
    area[p] += mesh.area(e);
  }
  double total = 0.0;
  for (uint32_t p = 0; p < mesh.patch_count(); ++p) {
    EXPECT_NEAR(area[p], mesh.patch_area(p), 1e-4 * area[p] + 1e-7);
    total += area[p];
    uint32_t element = 0;
    const Vec3 x = mesh.sample_patch(p, to_unit_float(mix64(p)), Vec2(0.3f, 0.6f), &element);
    EXPECT_EQ(mesh.patch_of(element), p);
    EXPECT_NEAR(length(x), 1.0f, 0.01f);
  }
  EXPECT_NEAR(total, mesh.total_area(), 1e-3 * total);
}

TEST(RadiosityAdaptive, PatchCountFollowsTheRayBudget) {
  RadiosityFixture f(floor_and_sphere(300));
  const uint32_t per_patch = RadiosityMeshSettings{}.min_rays_per_patch;
  for (uint64_t rays : {200000ull, 1000000ull, 3000000ull}) {
    const RadiosityMesh mesh = automatic_mesh(f, rays);
    const size_t cap = rays / per_patch;
    EXPECT_LE(mesh.patch_count(), cap) << rays << " rays";
    EXPECT_GE(mesh.patch_count(), cap / 2) << rays << " rays";
    EXPECT_GT(floor_elements(mesh), 100u) << rays << " rays";
  }
}

// A closed box of 6 x 2 x 40 x 40 tiny triangles emitting Le and reflecting rho: clustered into
// a few patches per face, the solve and the display must still give Le rho / (1 - rho) inside.
TEST(RadiosityAdaptive, ClusteredClosedBoxKeepsTheAnalyticValue) {
  Mesh box;
  const int k = 40;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = 0; sign < 2; ++sign) {
      const Vec3 n = [&] {
        Vec3 v(0.0f);
        v[axis] = sign ? 1.0f : -1.0f;
        return v;
      }();
      Vec3 u(0.0f), w(0.0f);
      u[(axis + 1) % 3] = 2.0f / k;
      w[(axis + 2) % 3] = 2.0f / k;
      if (!sign) std::swap(u, w);  // wind outwards
      const Vec3 origin = n - (u + w) * (0.5f * k);
      for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) {
          const uint32_t base = static_cast<uint32_t>(box.positions.size());
          const Vec3 p = origin + u * static_cast<float>(a) + w * static_cast<float>(b);
          box.positions.insert(box.positions.end(), {p, p + u, p + u + w, p + w});
          box.indices.insert(box.indices.end(),
                             {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    }
  const Vec3 rho(0.3f, 0.6f, 0.8f);
  Scene scene;
  scene.materials.push_back(Material::diffuse(rho).with_emission(Vec3(1.0f)));
  add_mesh_instance(&scene, box, 0);
  RadiosityFixture f(std::move(scene));
  const RadiosityMesh mesh = f.mesh(0.5f);  // triangles of 0.07 m: 4 x 4 clusters per face
  ASSERT_EQ(mesh.element_count(), 6u * 2 * k * k);
  EXPECT_LE(mesh.patch_count(), 6u * 5 * 5);
  EXPECT_GE(mesh.patch_count(), 6u * 4 * 4);
  RadiositySolveSettings s;
  s.rays = 1000000;
  PrepareControl control;
  RadiositySolveStats stats;
  const std::vector<RadiosityPower> power = solve_radiosity(f.context, mesh, s, control, &stats);
  ASSERT_EQ(power.size(), 2 * mesh.patch_count());
  const RadiosityField field(mesh, power);
  const Vec3 expected = rho / (Vec3(1.0f) - rho);
  double worst = 0.0;
  for (uint32_t p = 0; p < mesh.patch_count(); ++p) {
    const Vec3 l = field.patch_radiosity(p, 1).total() * kInvPi;  // inside: the back side
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(l[c] / expected[c] - 1.0));
    EXPECT_TRUE(is_black(field.patch_radiosity(p, 0).total()));
  }
  EXPECT_LT(worst, 0.1);
  // The smooth display (kernel over nearby clusters) keeps the value everywhere.
  double display_worst = 0.0;
  for (uint32_t e = 0; e < mesh.element_count(); e += 37) {
    uint32_t vertex[3];
    bool flip[3];
    mesh.element_vertices(e, vertex, flip);
    RadiosityLocation where;
    where.element = e;
    for (int c = 0; c < 3; ++c) where.vertex[c] = vertex[c], where.flip[c] = flip[c];
    where.weight[0] = where.weight[1] = where.weight[2] = 1.0f / 3.0f;
    const Vec3 l = field.radiosity_at(where, 1).total() * kInvPi;
    for (int c = 0; c < 3; ++c)
      display_worst = std::max(display_worst, std::fabs(l[c] / expected[c] - 1.0));
  }
  EXPECT_LT(display_worst, 0.1);
}

// Meshing (clusters, bisection), solve and the kernel display ignore the thread count.
TEST(RadiosityAdaptive, BitIdenticalWithOneAndTwoThreads) {
  RadiosityFixture lit([&] {
    Scene s = floor_and_sphere(200);
    Light sun;
    sun.type = LightType::kSun;
    sun.power = 3.0f;
    s.lights.push_back(sun);
    return s;
  }());
  std::vector<float> display[2];
  size_t patches[2] = {0, 0};
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const RadiosityMesh mesh = automatic_mesh(lit, 300000);
    patches[threads - 1] = mesh.patch_count();
    RadiositySolveSettings s;
    s.rays = 300000;
    PrepareControl control;
    RadiositySolveStats stats;
    const RadiosityField field(mesh, solve_radiosity(lit.context, mesh, s, control, &stats));
    ASSERT_FALSE(field.empty());
    for (uint32_t e = 0; e < mesh.element_count(); e += 7) {
      uint32_t vertex[3];
      bool flip[3];
      mesh.element_vertices(e, vertex, flip);
      RadiosityLocation where;
      where.element = e;
      for (int c = 0; c < 3; ++c) where.vertex[c] = vertex[c], where.flip[c] = flip[c];
      display[threads - 1].push_back(field.radiosity_at(where, 0).total().x);
    }
  }
  EXPECT_EQ(patches[0], patches[1]);
  ASSERT_EQ(display[0].size(), display[1].size());
  EXPECT_EQ(0,
            std::memcmp(display[0].data(), display[1].data(), display[0].size() * sizeof(float)));
  float largest = 0.0f;
  for (float v : display[0]) largest = std::max(largest, v);
  EXPECT_GT(largest, 0.0f);  // the sun lit something
}

}  // namespace
}  // namespace radiosity_adaptive_test
}  // namespace photon

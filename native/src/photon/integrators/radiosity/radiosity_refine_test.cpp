// Local refinement of the radiosity mesh where the light changes (radiosity_refine.h).
#include "photon/integrators/radiosity/radiosity_refine.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>

#include "photon/integrators/radiosity/radiosity_field.h"
#include "photon/testing/radiosity_test_util.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace radiosity_refine_test {
namespace {

constexpr float kHalf = 2.0f;  // the occluder covers |x|, |y| < 2, so does its shadow

// A 20 m floor (instance 0) under a sun shining straight down, and a 4 m square 2 m above it
// (instance 1) casting a sharp square shadow.
Scene shadowed_floor() {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  add_mesh_instance(&scene, make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 0);
  add_mesh_instance(&scene, make_quad({-kHalf, -kHalf, 2}, {2 * kHalf, 0, 0}, {0, 2 * kHalf, 0}),
                    0);
  Light sun;
  sun.type = LightType::kSun;
  sun.power = 3.0f;
  scene.lights.push_back(sun);
  return scene;
}

bool in_shadow(const Vec3& p) {
  return std::fabs(p.x) < kHalf && std::fabs(p.y) < kHalf;
}

// Distance of a floor point from the shadow square's outline.
float edge_distance(const Vec3& p) {
  const float dx = std::fabs(p.x) - kHalf, dy = std::fabs(p.y) - kHalf;
  if (dx < 0.0f && dy < 0.0f) return -std::max(dx, dy);
  return std::sqrt(std::max(dx, 0.0f) * std::max(dx, 0.0f) +
                   std::max(dy, 0.0f) * std::max(dy, 0.0f));
}

float median(std::vector<float> v) {
  if (v.empty()) return 0.0f;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

RadiosityRefined solve(RadiosityFixture& f, uint64_t rays, bool refine) {
  RadiosityMeshSettings ms;
  ms.rays = rays;
  RadiositySolveSettings s;
  s.rays = rays;
  RadiosityRefineSettings r;
  r.enabled = refine;
  PrepareControl control;
  return solve_radiosity_refined(f.context, ms, s, r, control, &f.warnings);
}

// Median area of the floor patches the shadow outline crosses, and of those far from it.
void floor_patch_areas(const RadiosityMesh& mesh, float* crossing, float* far) {
  std::vector<float> cross_areas, far_areas;
  for (uint32_t p = 0; p < mesh.patch_count(); ++p) {
    if (mesh.patch_instance(p) != 0) continue;
    if (edge_distance(mesh.patch_centroid(p)) > 4.0f) far_areas.push_back(mesh.patch_area(p));
  }
  // Patches with element corners on both sides of the outline.
  std::vector<uint8_t> side(mesh.patch_count(), 0);  // bit 0: a corner in shadow, bit 1: lit
  for (uint32_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) side[mesh.patch_of(e)] |= in_shadow(mesh.corner(e, k)) ? 1 : 2;
  for (uint32_t p = 0; p < mesh.patch_count(); ++p)
    if (mesh.patch_instance(p) == 0 && side[p] == 3) cross_areas.push_back(mesh.patch_area(p));
  *crossing = median(cross_areas);
  *far = median(far_areas);
}

TEST(RadiosityRefine, ShadowOutlineGetsSmallerPatchesWithinTheBudget) {
  RadiosityFixture f(shadowed_floor());
  constexpr uint64_t kRays = 2000000;
  float crossing[2], far[2];
  size_t patches[2];
  for (bool refine : {false, true}) {
    const RadiosityRefined r = solve(f, kRays, refine);
    ASSERT_FALSE(r.power.empty());
    floor_patch_areas(r.mesh, &crossing[refine], &far[refine]);
    patches[refine] = r.mesh.patch_count();
    ASSERT_GT(crossing[refine], 0.0f);
    ASSERT_GT(far[refine], 0.0f);
    if (refine) {
      EXPECT_GT(r.mesh.split_count(), 0u);
      EXPECT_LT(r.first_patches, r.mesh.patch_count());
      // Within the ray budget of the final solve (and the automatic patch target).
      const RadiosityMeshSettings ms;
      EXPECT_LE(r.mesh.patch_count(), kRays / ms.min_rays_per_patch);
      EXPECT_LE(r.mesh.patch_count(), ms.auto_elements);
      // The final solve has all the rays, each refinement pass a share more.
      const RadiosityRefineSettings rs;
      EXPECT_LE(r.stats.rays, kRays * (1.0 + rs.levels * rs.first_pass_rays) + kRays / 50);
    }
  }
  // The area sizing alone gives the floor patches one size.
  EXPECT_GT(crossing[0], 0.5f * far[0]);
  // Refined: the outline's patches are split 2 x 2, the uniformly lit floor is not.
  EXPECT_LE(crossing[1], 0.25f * far[1] * 1.001f);
  EXPECT_LE(patches[1], patches[0] * 1.01 + 64);
}

// Elements still tile the surfaces: patch areas add up, every element is located back to
// itself, and split patches are a quarter of their neighbours.
TEST(RadiosityRefine, RefinedMeshIsConsistent) {
  RadiosityFixture f(shadowed_floor());
  const RadiosityRefined r = solve(f, 1000000, true);
  const RadiosityMesh& mesh = r.mesh;
  ASSERT_GT(mesh.split_count(), 0u);
  double total = 0.0;
  std::vector<double> area(mesh.patch_count(), 0.0);
  for (uint32_t e = 0; e < mesh.element_count(); ++e) area[mesh.patch_of(e)] += mesh.area(e);
  for (uint32_t p = 0; p < mesh.patch_count(); ++p) {
    EXPECT_NEAR(area[p], mesh.patch_area(p), 1e-4 * area[p]);
    total += area[p];
  }
  EXPECT_NEAR(total, mesh.total_area(), 1e-4 * total);
  for (uint32_t e = 0; e < mesh.element_count(); ++e) {
    const Vec3 c = (mesh.corner(e, 0) + mesh.corner(e, 1) + mesh.corner(e, 2)) * (1.0f / 3.0f);
    const RadiosityElement& el = mesh.element(e);
    const RadiosityTriangle& t = mesh.triangle_of(e);
    // Barycentrics of the centroid in its triangle.
    const Vec3 d = c - t.p0;
    const float d11 = dot(t.e1, t.e1), d12 = dot(t.e1, t.e2), d22 = dot(t.e2, t.e2);
    const float d1 = dot(d, t.e1), d2 = dot(d, t.e2), den = d11 * d22 - d12 * d12;
    const float u = (d22 * d1 - d12 * d2) / den, v = (d11 * d2 - d12 * d1) / den;
    RadiosityLocation where;
    const uint32_t instance = el.triangle < 2 ? 0 : 1, primitive = el.triangle % 2;
    ASSERT_TRUE(mesh.locate(instance, primitive, u, v, &where));
    EXPECT_EQ(where.element, e);
  }
  // Sizes in use on the floor: the first mesh's divided by 4 per level.
  size_t by_level[4] = {0, 0, 0, 0};
  float largest = 0.0f;
  for (uint32_t p = 0; p < mesh.patch_count(); ++p)
    if (mesh.patch_instance(p) == 0) largest = std::max(largest, mesh.patch_area(p));
  for (uint32_t p = 0; p < mesh.patch_count(); ++p) {
    if (mesh.patch_instance(p) != 0) continue;
    const uint32_t level = mesh.patch_cell(p).level;
    ASSERT_LE(level, RadiosityRefineSettings{}.levels);
    ++by_level[level];
    const float expected = largest / static_cast<float>(1u << (2 * level));
    EXPECT_NEAR(mesh.patch_area(p), expected, 1e-3f * expected);
  }
  EXPECT_GT(by_level[2], 0u);  // refined again where the first split did not resolve the edge
}

// Where a large element meets smaller ones (T-vertices on its edge), the display is continuous:
// points just either side of the edge show the same radiosity.
TEST(RadiosityRefine, DisplayHasNoCracksAtTVertices) {
  RadiosityFixture f(shadowed_floor());
  const RadiosityRefined r = solve(f, 1000000, true);
  const RadiosityMesh& mesh = r.mesh;
  const RadiosityField field(mesh, r.power);
  ASSERT_FALSE(field.empty());
  uint32_t floor_element[2] = {UINT32_MAX, UINT32_MAX};  // one element of each floor triangle
  for (uint32_t e = 0; e < mesh.element_count(); ++e)
    if (mesh.element(e).triangle < 2) floor_element[mesh.element(e).triangle] = e;
  // The radiosity shown at floor point p (front side), and the element there.
  auto shown = [&](const Vec3& p, uint32_t* element) {
    for (uint32_t tri = 0; tri < 2; ++tri) {
      const RadiosityTriangle& t = mesh.triangle_of(floor_element[tri]);
      const Vec3 d = p - t.p0;
      const float d11 = dot(t.e1, t.e1), d12 = dot(t.e1, t.e2), d22 = dot(t.e2, t.e2);
      const float d1 = dot(d, t.e1), d2 = dot(d, t.e2), den = d11 * d22 - d12 * d12;
      const float u = (d22 * d1 - d12 * d2) / den, v = (d11 * d2 - d12 * d1) / den;
      if (u < 0.0f || v < 0.0f || u + v > 1.0f) continue;
      RadiosityLocation where;
      if (!mesh.locate(0, tri, u, v, &where)) break;
      *element = where.element;
      return field.radiosity_at(where, 0).total().x;
    }
    *element = UINT32_MAX;
    return -1.0f;
  };
  size_t t_edges = 0;
  double worst = 0.0, largest = 0.0;
  for (uint32_t e = 0; e < mesh.element_count(); ++e) {
    if (mesh.element(e).triangle >= 2 || mesh.element_shift(e) == 0) continue;
    const Vec3 centre = (mesh.corner(e, 0) + mesh.corner(e, 1) + mesh.corner(e, 2)) / 3.0f;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = mesh.corner(e, k), b = mesh.corner(e, (k + 1) % 3);
      for (float t : {0.3f, 0.5f, 0.7f}) {
        const Vec3 p = a + (b - a) * t;
        const Vec3 out = p + (p - centre) * 2e-3f, in = p - (p - centre) * 2e-3f;
        uint32_t e_in, e_out;
        const float v_in = shown(in, &e_in), v_out = shown(out, &e_out);
        if (e_in != e || e_out == UINT32_MAX || mesh.element_shift(e_out) >= mesh.element_shift(e))
          continue;  // outside the floor, or the neighbour is not smaller
        ++t_edges;
        worst = std::max(worst, static_cast<double>(std::fabs(v_in - v_out)));
        largest = std::max(largest, static_cast<double>(std::max(v_in, v_out)));
      }
    }
  }
  ASSERT_GT(t_edges, 10u);
  ASSERT_GT(largest, 0.0);
  // Within what the 0.2% step off the edge changes (the shading ramps across a patch or two).
  EXPECT_LT(worst, 0.02 * largest);
}

// The refined solve (passes of solve, marking and meshing, then the final solve) ignores the thread
// count.
TEST(RadiosityRefine, BitIdenticalWithOneAndTwoThreads) {
  RadiosityFixture f(shadowed_floor());
  std::vector<float> display[2];
  size_t splits[2] = {0, 0};
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const RadiosityRefined r = solve(f, 400000, true);
    splits[threads - 1] = r.mesh.split_count();
    const RadiosityField field(r.mesh, r.power);
    ASSERT_FALSE(field.empty());
    for (uint32_t e = 0; e < r.mesh.element_count(); e += 3) {
      RadiosityLocation where;
      where.element = e;
      r.mesh.element_vertices(e, where.vertex, where.flip);
      display[threads - 1].push_back(field.radiosity_at(where, 0).total().x);
    }
  }
  EXPECT_GT(splits[0], 0u);
  EXPECT_EQ(splits[0], splits[1]);
  ASSERT_EQ(display[0].size(), display[1].size());
  EXPECT_EQ(0,
            std::memcmp(display[0].data(), display[1].data(), display[0].size() * sizeof(float)));
}

}  // namespace
}  // namespace radiosity_refine_test
}  // namespace photon

// The faster first frame (parallel mesh import and cleanup, concurrent bottom-level builds, the
// LOW-quality BVH for previews) must not change what a ray hits or which triangles survive.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "photon/render/accel.h"
#include "photon/scene/mesh_import.h"
#include "photon/session/scene_resources.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace first_pixel_perf_test {
namespace {

// Many small meshes (each its own bottom-level BVH, built concurrently) plus one dense one.
Scene many_mesh_scene() {
  Scene scene = make_cornell_box();
  for (int i = 0; i < 64; ++i) {
    const Vec3 centre(0.1f + 0.1f * (i % 8), 0.1f + 0.1f * (i / 8), 0.3f + 0.01f * i);
    add_mesh_instance(&scene, make_uv_sphere(centre, 0.04f, 12, 8), 0);
  }
  add_mesh_instance(&scene, make_uv_sphere({0.5f, 0.5f, 0.7f}, 0.2f, 256, 128), 0);
  return scene;
}

std::vector<Ray> random_rays(size_t count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    r.origin = Vec3(u(rng), u(rng), u(rng));
    r.direction = normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    r.tmin = 0.0f;
    r.tmax = INFINITY;
  }
  return rays;
}

TEST(FirstPixelPerf, FastBuildBvhHitsExactlyWhatTheFastTraceBvhHits) {
  const Scene scene = many_mesh_scene();
  std::vector<std::string> warnings;
  const Accel trace(scene, &warnings, nullptr, BvhQuality::kFastTrace);
  const Accel build(scene, &warnings, nullptr, BvhQuality::kFastBuild);
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(trace.blas_count(), build.blas_count());
  EXPECT_EQ(trace.blas_count(), scene.meshes.size());
  size_t hits = 0;
  for (const Ray& ray : random_rays(20000)) {
    Hit a, b;
    const bool ha = trace.intersect(ray, kVisibleAll, &a);
    const bool hb = build.intersect(ray, kVisibleAll, &b);
    ASSERT_EQ(ha, hb);
    if (!ha) continue;
    ++hits;
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.u, b.u);
    EXPECT_EQ(a.v, b.v);
    EXPECT_EQ(a.instance, b.instance);
    EXPECT_EQ(a.primitive, b.primitive);
  }
  EXPECT_GT(hits, 15000u);
}

TEST(FirstPixelPerf, SharedAndCopiedVertexArraysHitTheSame) {
  Scene shared = many_mesh_scene();
  Scene copied = shared;
  for (Mesh& mesh : shared.meshes) mesh.positions.reserve(mesh.positions.size() + 1);
  for (Mesh& mesh : copied.meshes) mesh.positions.shrink_to_fit();
  const Accel a(shared, nullptr), b(copied, nullptr);
  for (const Ray& ray : random_rays(5000)) {
    Hit ha, hb;
    ASSERT_EQ(a.intersect(ray, kVisibleAll, &ha), b.intersect(ray, kVisibleAll, &hb));
    EXPECT_EQ(ha.t, hb.t);
    EXPECT_EQ(ha.primitive, hb.primitive);
  }
  EXPECT_EQ(a.triangle_count(), b.triangle_count());
}

TEST(FirstPixelPerf, ConcurrentBottomLevelBuildsMatchBruteForce) {
  const Scene scene = many_mesh_scene();
  const Accel accel(scene, nullptr);
  // Closest hit by testing every triangle of every instance (Moller-Trumbore), for comparison.
  auto brute = [&](const Ray& ray, float* t_best, uint32_t* instance) {
    bool found = false;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
      const Mesh& mesh = scene.meshes[scene.instances[i].mesh];
      const Transform& xf = scene.instances[i].object_to_world;
      for (size_t k = 0; k < mesh.triangle_count(); ++k) {
        const Vec3 p0 = xf.point(mesh.positions[mesh.indices[3 * k]]);
        const Vec3 e1 = xf.point(mesh.positions[mesh.indices[3 * k + 1]]) - p0;
        const Vec3 e2 = xf.point(mesh.positions[mesh.indices[3 * k + 2]]) - p0;
        const Vec3 pv = cross(ray.direction, e2);
        const float det = dot(e1, pv);
        if (std::fabs(det) < 1e-12f) continue;
        const Vec3 tv = ray.origin - p0;
        const float u = dot(tv, pv) / det;
        const Vec3 qv = cross(tv, e1);
        const float v = dot(ray.direction, qv) / det;
        const float t = dot(e2, qv) / det;
        if (u < 0 || v < 0 || u + v > 1 || t <= 0 || t >= *t_best) continue;
        *t_best = t;
        *instance = i;
        found = true;
      }
    }
    return found;
  };
  for (const Ray& ray : random_rays(300)) {
    float t = INFINITY;
    uint32_t instance = UINT32_MAX;
    const bool expected = brute(ray, &t, &instance);
    Hit hit;
    ASSERT_EQ(accel.intersect(ray, kVisibleAll, &hit), expected);
    if (!expected) continue;
    EXPECT_NEAR(hit.t, t, 1e-4f * (1.0f + t));
    EXPECT_EQ(accel.scene_instance(hit.instance), instance);
  }
}

TEST(FirstPixelPerf, PreviewOfABigMeshGetsTheFastBuildAndFinalRendersTheFastTrace) {
  Scene scene = make_cornell_box();
  add_mesh_instance(&scene, make_uv_sphere({0.5f, 0.5f, 0.5f}, 0.2f, 512, 256), 0);  // ~260k
  RenderSettings preview;
  preview.integrator = IntegratorType::kRayTrace;
  preview.full_width = preview.full_height = preview.x1 = preview.y1 = 1;
  preview.samples = 1;
  EXPECT_EQ(bvh_quality_for(scene, preview), BvhQuality::kFastBuild);

  RenderSettings final_render = preview;
  final_render.full_width = final_render.x1 = 1920;
  final_render.full_height = final_render.y1 = 1080;
  final_render.samples = 16;
  EXPECT_EQ(bvh_quality_for(scene, final_render), BvhQuality::kFastTrace);

  // The photon pre-pass alone traces more rays than a quarter of the triangles.
  RenderSettings photons = preview;
  photons.integrator = IntegratorType::kPhotonMap;
  photons.photons = 1000000;
  EXPECT_EQ(bvh_quality_for(scene, photons), BvhQuality::kFastTrace);

  // A small scene is never worth a worse BVH, even for one ray.
  Scene small = make_cornell_box();
  add_mesh_instance(&small, make_uv_sphere({0.5f, 0.5f, 0.5f}, 0.2f, 128, 64), 0);  // ~16k
  EXPECT_EQ(bvh_quality_for(small, preview), BvhQuality::kFastTrace);
}

// The serial cleanup as it was before it went parallel: the reference the parallel one must
// reproduce exactly (same kept triangles, order, sanitised attributes and source numbering).
MeshCleanupReport serial_clean(Mesh* mesh) {
  MeshCleanupReport report;
  std::vector<uint8_t> bad(mesh->positions.size(), 0);
  for (size_t i = 0; i < mesh->positions.size(); ++i)
    if (!is_finite(mesh->positions[i])) {
      bad[i] = 1;
      mesh->positions[i] = Vec3(0.0f);
      ++report.non_finite_vertices;
    }
  Mesh out = *mesh;
  out.indices.clear();
  out.corner_normals.clear();
  out.corner_uvs.clear();
  out.material_slots.clear();
  out.source_triangles.clear();
  const size_t n = mesh->positions.size();
  for (size_t t = 0; t < mesh->triangle_count(); ++t) {
    const uint32_t* i = &mesh->indices[3 * t];
    bool ok = i[0] < n && i[1] < n && i[2] < n && !bad[i[0]] && !bad[i[1]] && !bad[i[2]] &&
              i[0] != i[1] && i[1] != i[2] && i[0] != i[2];
    if (ok) {
      const Vec3 e1 = mesh->positions[i[1]] - mesh->positions[i[0]];
      const Vec3 e2 = mesh->positions[i[2]] - mesh->positions[i[0]];
      const float area2 = length(cross(e1, e2));
      ok = std::isfinite(area2) &&
           area2 > 1e-12f * std::max(length_squared(e1), length_squared(e2)) && area2 > 0.0f;
    }
    if (!ok) {
      ++report.dropped_triangles;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      out.indices.push_back(i[c]);
      const Vec3 nrm = mesh->corner_normals[3 * t + c];
      out.corner_normals.push_back(is_finite(nrm) && length_squared(nrm) > 0 ? nrm : Vec3(0.0f));
      const Vec2 uv = mesh->corner_uvs[3 * t + c];
      out.corner_uvs.push_back(std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : Vec2(0.0f, 0.0f));
    }
    out.material_slots.push_back(mesh->material_slots[t]);
    out.source_triangles.push_back(static_cast<uint32_t>(t));
  }
  if (out.source_triangles.size() == mesh->triangle_count()) out.source_triangles.clear();
  *mesh = std::move(out);
  return report;
}

TEST(FirstPixelPerf, ParallelCleanupOfALargeMeshMatchesTheSerialOne) {
  // Larger than the parallel grain, with bad data scattered through every block.
  Mesh mesh = make_uv_sphere({0.0f, 0.0f, 0.0f}, 1.0f, 400, 300);
  const size_t tris = mesh.triangle_count();
  mesh.corner_normals.assign(3 * tris, Vec3(0.0f, 0.0f, 1.0f));
  mesh.corner_uvs.assign(3 * tris, Vec2(0.25f, 0.75f));
  mesh.material_slots.assign(tris, 0);
  std::mt19937 rng(3);
  for (size_t t = 0; t < tris; ++t) mesh.material_slots[t] = static_cast<int32_t>(t % 5);
  for (int k = 0; k < 2000; ++k) {
    const size_t t = rng() % tris;
    switch (k % 5) {
      case 0:
        mesh.indices[3 * t] = mesh.indices[3 * t + 1];
        break;  // degenerate
      case 1:
        mesh.indices[3 * t + 2] = UINT32_MAX;
        break;  // out of range
      case 2:
        mesh.positions[rng() % mesh.positions.size()].x = NAN;
        break;  // bad vertex
      case 3:
        mesh.corner_normals[3 * t + 1] = Vec3(NAN, 0.0f, 0.0f);
        break;
      default:
        mesh.corner_uvs[3 * t + 2] = Vec2(INFINITY, 0.0f);
        break;
    }
  }
  Mesh expected = mesh;
  const MeshCleanupReport want = serial_clean(&expected);
  const MeshCleanupReport got = clean_mesh(&mesh);
  ASSERT_GT(want.dropped_triangles, 0u);
  EXPECT_EQ(got.dropped_triangles, want.dropped_triangles);
  EXPECT_EQ(got.non_finite_vertices, want.non_finite_vertices);
  EXPECT_EQ(mesh.indices, expected.indices);
  EXPECT_EQ(mesh.material_slots, expected.material_slots);
  EXPECT_EQ(mesh.source_triangles, expected.source_triangles);
  ASSERT_EQ(mesh.corner_normals.size(), expected.corner_normals.size());
  for (size_t i = 0; i < mesh.corner_normals.size(); ++i) {
    ASSERT_EQ(mesh.corner_normals[i].x, expected.corner_normals[i].x) << i;
    ASSERT_EQ(mesh.corner_uvs[i].x, expected.corner_uvs[i].x) << i;
  }
}

TEST(FirstPixelPerf, ParallelLoopGatherOfALargeMeshPicksEachCornersLoop) {
  // 3 * 200k corners through a shuffled loop table, with a few invalid loops and vertices.
  const size_t vertices = 50000, loops = 150000, corners = 600000;
  std::mt19937 rng(11);
  std::vector<int32_t> loop_vertices(loops), corner_loops(corners);
  std::vector<float> loop_uvs(2 * loops), loop_normals(3 * loops);
  for (size_t l = 0; l < loops; ++l) {
    loop_vertices[l] = static_cast<int32_t>(rng() % (vertices + 10));  // some out of range
    loop_uvs[2 * l] = static_cast<float>(l);
    loop_normals[3 * l + 2] = static_cast<float>(l);
  }
  for (size_t k = 0; k < corners; ++k)
    corner_loops[k] = k % 997 == 0 ? -1 : static_cast<int32_t>(rng() % loops);
  Mesh mesh;
  mesh.positions.assign(vertices, Vec3(0.0f));
  LoopMeshView view;
  view.corner_loops = corner_loops.data();
  view.corner_count = corners;
  view.loop_vertices = loop_vertices.data();
  view.loop_count = loops;
  view.loop_uvs = loop_uvs.data();
  view.loop_normals = loop_normals.data();
  gather_loop_mesh(view, &mesh);
  ASSERT_EQ(mesh.indices.size(), corners);
  for (size_t k = 0; k < corners; ++k) {
    const int32_t l = corner_loops[k];
    const bool loop_ok = l >= 0;
    const bool vertex_ok = loop_ok && static_cast<size_t>(loop_vertices[l]) < vertices;
    ASSERT_EQ(mesh.indices[k], vertex_ok ? static_cast<uint32_t>(loop_vertices[l]) : UINT32_MAX);
    ASSERT_EQ(mesh.corner_uvs[k].x, loop_ok ? static_cast<float>(l) : 0.0f);
    ASSERT_EQ(mesh.corner_normals[k].z, loop_ok ? static_cast<float>(l) : 0.0f);
  }
}

}  // namespace
}  // namespace first_pixel_perf_test
}  // namespace photon

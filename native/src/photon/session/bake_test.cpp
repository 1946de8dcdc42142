#include "photon/session/bake.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "photon/render/accel.h"
#include "photon/session/lightmap.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace bake_test {
namespace {

RenderSettings bake_settings(int samples = 8) {
  RenderSettings s;
  s.samples = samples;
  s.seed = 5;
  s.photons = 50000;
  s.caustic_photons = 0;
  s.integrator = IntegratorType::kPhotonMap;
  return s;
}

// Barycentrics (u, v) of point (x, y) on triangle (p0, p1, p2) of make_quad's first triangle.
BakePoint point_on(uint32_t instance, uint32_t triangle, float u, float v) {
  BakePoint p;
  p.instance = instance;
  p.triangle = triangle;
  p.u = u;
  p.v = v;
  return p;
}

// The bake point of instance 0 straight below (x, y) (traced, so no assumption on how the
// mesh is triangulated); false if nothing is there.
bool point_below(const Accel& accel, float x, float y, float z_above, BakePoint* point) {
  Ray ray;
  ray.origin = Vec3(x, y, z_above);
  ray.direction = Vec3(0, 0, -1);
  Hit hit;
  if (!accel.intersect(ray, kVisibleAll, &hit)) return false;
  *point = point_on(0, hit.primitive, hit.u, hit.v);
  return true;
}

// A point light of `power` W at (0, 0, height).
Light point_light_above(float power, float height) {
  Light light;
  light.power = power;
  light.light_to_world = Transform::translation(Vec3(0, 0, height));
  return light;
}

TEST(Accel, SurfaceHitMatchesTheHitOfARay) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  const Transform xf = Transform::from_rows(
      std::array<float, 12>{0, -2, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3}.data());  // rotate, scale, move
  add_mesh_instance(&scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0, xf);
  const Accel accel(scene, nullptr);
  Ray ray;
  ray.origin = Vec3(1.3f, 2.2f, 5.0f);
  ray.direction = Vec3(0, 0, -1);
  Hit traced;
  ASSERT_TRUE(accel.intersect(ray, kVisibleAll, &traced));
  Hit made;
  ASSERT_TRUE(accel.surface_hit(0, traced.primitive, traced.u, traced.v, &made));
  EXPECT_NEAR(made.p.x, traced.p.x, 1e-5f);
  EXPECT_NEAR(made.p.y, traced.p.y, 1e-5f);
  EXPECT_NEAR(made.p.z, traced.p.z, 1e-5f);
  // Same geometric normal direction (Embree's is unnormalised): shading sees the same side.
  const SurfaceInteraction a = accel.interaction(traced), b = accel.interaction(made);
  EXPECT_GT(dot(a.ng, b.ng), 0.999f);
  EXPECT_FALSE(accel.surface_hit(1, 0, 0.2f, 0.2f, &made));  // no such instance
  EXPECT_FALSE(accel.surface_hit(0, 2, 0.2f, 0.2f, &made));  // a quad has two triangles
}

// A plane under a point light of intensity I at height h: L = albedo / pi * I cos / d^2 (no
// other surface, so no indirect light), on the lit side whichever way the normal points.
TEST(Bake, PlaneUnderPointLightFollowsInverseSquareLawOnBothWindings) {
  for (bool flipped : {false, true}) {
    Scene scene;
    scene.materials.push_back(Material::diffuse(Vec3(0.5f)));
    Mesh quad = make_quad({-10, -10, 0}, {20, 0, 0}, {0, 20, 0});
    if (flipped)
      for (size_t t = 0; t < quad.triangle_count(); ++t)
        std::swap(quad.indices[3 * t + 1], quad.indices[3 * t + 2]);
    add_mesh_instance(&scene, quad, 0);
    scene.lights.push_back(point_light_above(100.0f, 1.0f));
    const Accel accel(scene, nullptr);
    std::vector<BakePoint> points;
    std::vector<Vec3> where = {{0, 0, 0}, {0.3f, 0, 0}, {-1.0f, 2.0f, 0}};
    for (const Vec3& w : where) {
      points.emplace_back();
      ASSERT_TRUE(point_below(accel, w.x, w.y, 0.5f, &points.back()));
    }
    const BakeResult r =
        bake_points(scene, bake_settings(), BakeOptions{}, points, PrepareControl{});
    ASSERT_TRUE(r.error.empty()) << r.error;
    const double intensity = 100.0 / (4.0 * kPi);
    for (size_t i = 0; i < where.size(); ++i) {
      ASSERT_EQ(r.status[i], kBakeOk);
      const double d2 = 1.0 + where[i].x * where[i].x + where[i].y * where[i].y;
      const double expected = 0.5 / kPi * intensity / std::sqrt(d2) / d2;
      EXPECT_NEAR(r.radiance[i].x, expected, 0.01 * expected)
          << "point " << i << " flipped " << flipped;
      EXPECT_GT(r.normal[i].z, 0.99f);  // the lit side was kept
    }
    // Front side only: a flipped plane bakes its dark underside.
    BakeOptions front;
    front.brighter_side = false;
    const BakeResult f = bake_points(scene, bake_settings(), front, points, PrepareControl{});
    EXPECT_EQ(f.radiance[0].x == 0.0f, flipped);
  }
}

// Closed emissive box of albedo rho: L = Le / (1 - rho) everywhere; checks emission, direct
// light from emissive meshes and final gathering together, and thread independence.
TEST(Bake, EmissiveFurnaceAndThreadIndependence) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.6f)).with_emission(Vec3(1.0f)));
  add_mesh_instance(&scene, make_box({-1, -1, -1}, {1, 1, 1}), 0);
  std::vector<BakePoint> points;
  for (uint32_t t = 0; t < 12; ++t) points.push_back(point_on(0, t, 0.3f, 0.4f));
  RenderSettings s = bake_settings(16);
  s.threads = 1;
  const BakeResult one = bake_points(scene, s, BakeOptions{}, points, PrepareControl{});
  s.threads = 2;
  const BakeResult two = bake_points(scene, s, BakeOptions{}, points, PrepareControl{});
  double mean = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(one.status[i], kBakeOk);
    EXPECT_EQ(one.radiance[i].x, two.radiance[i].x);
    EXPECT_EQ(one.radiance[i].y, two.radiance[i].y);
    mean += one.radiance[i].x / points.size();
  }
  EXPECT_NEAR(mean, 1.0 / (1.0 - 0.6), 0.03 * 2.5);
}

TEST(Bake, AddressesTrianglesByTheCallersNumberingAfterDrops) {
  Scene scene;
  scene.materials.push_back(Material::diffuse(Vec3(0.8f)));
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  mesh.indices = {0, 0, 1,   // degenerate: dropped
                  0, 1, 2};  // caller's triangle 1, the mesh's triangle 0 after the cleanup
  clean_mesh(&mesh);
  ASSERT_EQ(mesh.triangle_count(), 1u);
  add_mesh_instance(&scene, mesh, 0);
  Light light;
  light.light_to_world = Transform::translation(Vec3(0, 0, 1));
  scene.lights.push_back(light);
  const std::vector<BakePoint> points = {point_on(0, 1, 0.25f, 0.5f), point_on(0, 0, 0.2f, 0.2f),
                                         point_on(0, 7, 0.2f, 0.2f), point_on(3, 1, 0.2f, 0.2f)};
  const BakeResult r = bake_points(scene, bake_settings(), BakeOptions{}, points, PrepareControl{});
  EXPECT_EQ(r.status[0], kBakeOk);
  EXPECT_NEAR(r.position[0].x, 0.25f, 1e-6f);
  EXPECT_NEAR(r.position[0].y, 0.5f, 1e-6f);
  EXPECT_GT(r.radiance[0].x, 0.0f);
  EXPECT_EQ(r.status[1], kBakeInvalidPoint);  // the dropped triangle
  EXPECT_EQ(r.status[2], kBakeInvalidPoint);  // out of range
  EXPECT_EQ(r.status[3], kBakeInvalidPoint);  // no such instance
  EXPECT_FALSE(r.warnings.empty());
}

TEST(Bake, MirrorsAreUnsupportedAndRayTracingCannotBake) {
  Scene scene;
  scene.materials.push_back(Material::mirror(Vec3(0.9f)));
  add_mesh_instance(&scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0);
  const std::vector<BakePoint> points = {point_on(0, 0, 0.2f, 0.2f)};
  const BakeResult r = bake_points(scene, bake_settings(), BakeOptions{}, points, PrepareControl{});
  EXPECT_EQ(r.status[0], kBakeUnsupported);
  EXPECT_FALSE(r.error.empty());  // nothing at all could be baked
  RenderSettings rt = bake_settings();
  rt.integrator = IntegratorType::kRayTrace;
  EXPECT_NE(bake_points(scene, rt, BakeOptions{}, points, PrepareControl{}).error.find("RAY_TRACE"),
            std::string::npos);
}

TEST(Bake, CancelBeforeShadingLeavesPointsNotDone) {
  Scene scene = make_cornell_box();
  std::atomic<bool> cancel{true};
  PrepareControl control;
  control.cancel = &cancel;
  const BakeResult r =
      bake_points(scene, bake_settings(), BakeOptions{}, {point_on(0, 0, 0.2f, 0.2f)}, control);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.status[0], kBakeNotDone);
  EXPECT_TRUE(r.error.empty());
}

TEST(Lightmap, RasterisesEachCoveredTexelOnce) {
  // Two triangles covering the unit square, 8 x 8 texels: every texel exactly once, and the
  // barycentrics reproduce the texel centre.
  const Vec2 uvs[6] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
  const std::vector<TexelPoint> texels = rasterize_uv_triangles(uvs, nullptr, 2, 8, 8);
  ASSERT_EQ(texels.size(), 64u);
  std::vector<int> seen(64, 0);
  for (const TexelPoint& t : texels) {
    ++seen[t.texel];
    const Vec2* p = &uvs[3 * t.triangle];
    const float x = p[0].x * (1 - t.u - t.v) + p[1].x * t.u + p[2].x * t.v;
    const float y = p[0].y * (1 - t.u - t.v) + p[1].y * t.u + p[2].y * t.v;
    EXPECT_NEAR(x * 8, t.texel % 8 + 0.5f, 1e-4f);
    EXPECT_NEAR(y * 8, t.texel / 8 + 0.5f, 1e-4f);
  }
  for (int s : seen) EXPECT_EQ(s, 1);
  // A triangle over the left half only: 4 x 8 texels below the diagonal x + ... (half of it).
  const Vec2 half[3] = {{0, 0}, {0.5f, 0}, {0, 1}};
  const Vec3 world[3] = {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}};
  const std::vector<TexelPoint> h = rasterize_uv_triangles(half, world, 1, 8, 8);
  EXPECT_GT(h.size(), 8u);
  EXPECT_LT(h.size(), 24u);
  EXPECT_NEAR(h[0].world_size, 0.5f, 1e-5f);  // 2 m over 4 texels
}

TEST(Lightmap, FilterSmoothsASurfaceButNotAcrossSurfacesAndFillsGutters) {
  const int w = 8, h = 4;
  const size_t n = w * h;
  std::vector<Vec3> values(n), positions(n), normals(n, Vec3(0, 0, 1));
  std::vector<uint8_t> covered(n, 1);
  std::vector<float> size(n, 0.1f);
  // Columns 0-2: chart A (noisy around 1); column 3: gutter; columns 4-7: chart B (value 5),
  // far away on the surface although next to A in the texture.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = y * w + x;
      positions[i] = x < 4 ? Vec3(0.1f * x, 0.1f * y, 0) : Vec3(10 + 0.1f * x, 0.1f * y, 0);
      values[i] = x < 4 ? Vec3(((x + y) % 2) ? 1.2f : 0.8f) : Vec3(5.0f);
      if (x == 3) covered[i] = 0;
    }
  std::vector<uint8_t> out_cover;
  LightmapFilter filter;
  filter.radius = 1;
  filter.dilate = 1;
  const std::vector<Vec3> out =
      filter_lightmap(w, h, values, covered, positions, normals, size, filter, &out_cover);
  for (int y = 0; y < h; ++y) {
    EXPECT_NEAR(out[y * w + 1].x, 1.0f, 0.1f);  // smoothed towards the mean
    EXPECT_FLOAT_EQ(out[y * w + 5].x, 5.0f);    // chart B untouched by chart A
    EXPECT_TRUE(out_cover[y * w + 3]);          // the gutter was filled...
    EXPECT_GT(out[y * w + 3].x, 1.0f);          // ...from both neighbours
  }
}

// A bake reads textured albedo like a render does: a plane whose Diffuse colour comes from a
// 2 x 1 image (8-bit sRGB 255 and 128: linear 1 and 0.2158) bakes the two halves in that ratio.
TEST(Bake, TexturedAlbedoIsBaked) {
  const std::string dir = ::testing::TempDir();
  setenv("PHOTON_TEXTURE_CACHE", (dir + "photon_bake_tex_cache").c_str(), 1);
  const std::string path = dir + "photon_bake_two_texels.png";
  unsigned char px[6] = {255, 255, 255, 128, 128, 128};
  ASSERT_TRUE(OIIO::ImageBuf(OIIO::ImageSpec(2, 1, 3, OIIO::TypeDesc::UINT8), px).write(path));
  Scene scene;
  scene.textures.push_back({path, true, TextureExtension::kExtend, TextureInterpolation::kClosest});
  Material m = Material::diffuse(Vec3(0.8f));
  m.closures[0][Param::kColor].texture = 0;
  scene.materials.push_back(m);
  Mesh quad = make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0});
  quad.corner_uvs.clear();
  for (uint32_t i : quad.indices)
    quad.corner_uvs.push_back(
        Vec2(0.5f * (quad.positions[i].x + 1), 0.5f * (quad.positions[i].y + 1)));
  add_mesh_instance(&scene, quad, 0);
  scene.lights.push_back(point_light_above(100.0f, 3.0f));
  const Accel accel(scene, nullptr);
  std::vector<BakePoint> points;
  for (float x : {-0.5f, 0.5f}) {  // symmetric about the light: same irradiance
    points.emplace_back();
    ASSERT_TRUE(point_below(accel, x, 0.0f, 1.0f, &points.back()));
  }
  const BakeResult r = bake_points(scene, bake_settings(), BakeOptions{}, points, PrepareControl{});
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.status[0], kBakeOk);
  ASSERT_EQ(r.status[1], kBakeOk);
  EXPECT_NEAR(r.radiance[1].x / r.radiance[0].x, 0.2158f, 0.005f);
}

}  // namespace
}  // namespace bake_test
}  // namespace photon

namespace photon {
namespace bake_test {
namespace {

// Upsampling keeps texel centres aligned: a linear ramp stays the same ramp in between, the
// edges clamp, and alpha is 1.
TEST(Lightmap, UpsampleIsBilinearBetweenTexelCentres) {
  const int w = 4, h = 2, f = 4;
  std::vector<Vec3> ramp(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) ramp[y * w + x] = Vec3(static_cast<float>(x), 2.0f * y, 1.0f);
  std::vector<float> rgba(static_cast<size_t>(w * f) * h * f * 4, -1.0f);
  upsample_lightmap_rgba(ramp.data(), w, h, f, rgba.data());
  for (int y = 0; y < h * f; ++y)
    for (int x = 0; x < w * f; ++x) {
      const float* p = &rgba[(static_cast<size_t>(y) * w * f + x) * 4];
      const float sx = std::clamp((x + 0.5f) / f - 0.5f, 0.0f, w - 1.0f);
      const float sy = std::clamp((y + 0.5f) / f - 0.5f, 0.0f, h - 1.0f);
      EXPECT_NEAR(p[0], sx, 1e-5f) << x << ", " << y;
      EXPECT_NEAR(p[1], 2.0f * sy, 1e-5f) << x << ", " << y;
      EXPECT_EQ(p[2], 1.0f);
      EXPECT_EQ(p[3], 1.0f);
    }
}

}  // namespace
}  // namespace bake_test
}  // namespace photon

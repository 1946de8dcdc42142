// Each closure shades with its own Normal input (Cycles' closures each carry their N): a closure
// without one keeps the interpolated normal even when another closure of the material is
// normal-mapped, and an unlinked Clearcoat Normal is the interpolated normal too.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "photon/base/optics.h"
#include "photon/render/material_eval.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/test_util.h"

namespace photon {
namespace closure_normals_test {
namespace {

namespace fs = std::filesystem;

constexpr float kTilt = 0.5f;  // radians towards +u (= +x on the textured quad)

// A 1 x 1 tangent-space normal map tilting the normal by kTilt towards +u.
std::string tilted_normal_map() {
  const fs::path dir = fs::temp_directory_path() / "photon_closure_normals_test";
  fs::create_directories(dir);
  const std::string path = (dir / "tilt.exr").string();
  float px[3] = {0.5f + 0.5f * std::sin(kTilt), 0.5f, 0.5f + 0.5f * std::cos(kTilt)};
  EXPECT_TRUE(OIIO::ImageBuf(OIIO::ImageSpec(1, 1, 3, OIIO::TypeDesc::FLOAT), px).write(path));
  return path;
}

struct Shaded {
  Scene scene;
  std::unique_ptr<Accel> accel;
  std::unique_ptr<TextureSet> textures;
  ShadingPoint sp;
};

// Shades the centre of a textured quad facing +z, seen from straight above.
void shade_quad(Material m, Shaded* out) {
  setenv("PHOTON_TEXTURE_CACHE",
         (fs::temp_directory_path() / "photon_closure_normals_cache").c_str(), 1);
  out->scene.materials.push_back(std::move(m));
  out->scene.textures.push_back(
      {tilted_normal_map(), false, TextureExtension::kRepeat, TextureInterpolation::kLinear});
  add_mesh_instance(&out->scene, make_textured_quad(), 0);
  out->accel = std::make_unique<Accel>(out->scene, nullptr);
  out->textures = std::make_unique<TextureSet>(out->scene.textures, nullptr);
  Ray ray;
  ray.origin = Vec3(0.2f, 0.3f, 1.0f);
  ray.direction = Vec3(0, 0, -1);
  Hit hit;
  ASSERT_TRUE(out->accel->intersect(ray, kVisibleAll, &hit));
  out->sp =
      shade_surface(out->accel->interaction(hit), Vec3(0, 0, 1), *out->accel, out->textures.get());
}

// The direction a sharp mirror lobe of the BSDF reflects straight-down light to.
Vec3 mirror_direction(const Bsdf& bsdf) {
  BsdfSample s;
  EXPECT_TRUE(bsdf.sample(Vec3(0, 0, 1), 0.5f, Vec2(0.5f, 0.5f), kLobeSpecular, &s));
  return s.wi;
}

Closure mapped(Closure c) {
  c.normal.texture = 0;
  c.normal.strength = 1.0f;
  return c;
}

TEST(ClosureNormals, AClosureWithoutANormalKeepsTheInterpolatedOne) {
  const Vec3 tilted(std::sin(kTilt), 0.0f, std::cos(kTilt));
  // Mirror unmapped, diffuse normal-mapped: the mirror reflects about +z.
  Shaded a;
  const Closure mirror = Material::mirror(Vec3(1.0f)).closures[0];
  const Closure diffuse = Material::diffuse(Vec3(0.5f)).closures[0];
  shade_quad(Material{"mixed", {mirror, mapped(diffuse)}}, &a);
  EXPECT_TRUE(VecNear(mirror_direction(a.sp.bsdf), Vec3(0, 0, 1), 1e-4f));
  // The diffuse lobe shades about the tilted normal: no light from below its horizon.
  const Vec3 below_tilted = normalize(Vec3(-1.0f, 0.0f, 0.3f));
  ASSERT_LT(dot(below_tilted, tilted), 0.0f);
  EXPECT_TRUE(is_black(a.sp.bsdf.eval(Vec3(0, 0, 1), below_tilted, kLobeDiffuse)));
  EXPECT_FALSE(is_black(a.sp.bsdf.eval(Vec3(0, 0, 1), tilted, kLobeDiffuse)));

  // Both mapped: the mirror reflects about the tilted normal.
  Shaded b;
  shade_quad(Material{"both", {mapped(mirror), mapped(diffuse)}}, &b);
  EXPECT_TRUE(VecNear(mirror_direction(b.sp.bsdf), reflect(Vec3(0, 0, 1), tilted), 1e-3f));
}

TEST(ClosureNormals, UnlinkedClearcoatNormalIsTheInterpolatedNormal) {
  // A black, non-specular Principled whose only mirror is its sharp clearcoat: the Normal input
  // is mapped, the Clearcoat Normal is not, so the coat reflects about +z.
  Closure p;
  p.type = ClosureType::kPrincipled;
  p[Param::kColor] = Input::constant(0.0f);
  p[Param::kSpecular] = Input::constant(0.0f);
  p[Param::kClearcoat] = Input::constant(1.0f);
  p[Param::kClearcoatRoughness] = Input::constant(0.0f);
  Shaded s;
  shade_quad(Material{"coat", {mapped(p)}}, &s);
  EXPECT_TRUE(VecNear(s.sp.bsdf.frame().n, Vec3(std::sin(kTilt), 0.0f, std::cos(kTilt)), 2e-3f));
  EXPECT_TRUE(VecNear(mirror_direction(s.sp.bsdf), Vec3(0, 0, 1), 1e-4f));
}

}  // namespace
}  // namespace closure_normals_test
}  // namespace photon

#include "photon/render/material_eval.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "photon/testing/test_scenes.h"
#include "photon/testing/test_util.h"

namespace photon {
namespace material_eval_test {
namespace {

namespace fs = std::filesystem;

// A 2 x 2 RGBA PNG: top-left red, top-right green, bottom-left blue, bottom-right white with
// half alpha (8-bit sRGB values).
std::string write_quad_png(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "photon_material_eval_test";
  fs::create_directories(dir);
  const std::string path = (dir / name).string();
  const unsigned char px[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
  OIIO::ImageBuf buf(OIIO::ImageSpec(2, 2, 4, OIIO::TypeDesc::UINT8),
                     const_cast<unsigned char*>(px));
  EXPECT_TRUE(buf.write(path));
  return path;
}

struct TextureFixture : ::testing::Test {
  void SetUp() override {
    setenv("PHOTON_TEXTURE_CACHE",
           (fs::temp_directory_path() / "photon_material_eval_cache").c_str(), 1);
  }
};

using Textures = TextureFixture;

TEST_F(Textures, ClosestLookupsReturnLinearColourAndStraightAlpha) {
  ImageTexture tex;
  tex.path = write_quad_png("quad.png");
  tex.interpolation = TextureInterpolation::kClosest;
  std::vector<std::string> warnings;
  TextureSet set({tex}, &warnings);
  ASSERT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_TRUE(set.valid(0));
  float rgba[4];
  // Blender's v runs up: (0.25, 0.75) is the top-left texel.
  ASSERT_TRUE(set.lookup(0, Vec2(0.25f, 0.75f), rgba));
  EXPECT_NEAR(rgba[0], 1.0f, 1e-3f);
  EXPECT_NEAR(rgba[1], 0.0f, 1e-3f);
  ASSERT_TRUE(set.lookup(0, Vec2(0.25f, 0.25f), rgba));  // bottom-left: blue
  EXPECT_NEAR(rgba[2], 1.0f, 1e-3f);
  ASSERT_TRUE(set.lookup(0, Vec2(0.75f, 0.25f), rgba));  // white, alpha 128/255, not premultiplied
  EXPECT_NEAR(rgba[0], 1.0f, 1e-3f);
  EXPECT_NEAR(rgba[3], 128.0f / 255.0f, 2e-3f);
}

TEST_F(Textures, SrgbValuesAreLinearisedAndNonColorIsNot) {
  // A mid-grey 8-bit texel (sRGB 0.5 -> linear 0.214).
  const fs::path dir = fs::temp_directory_path() / "photon_material_eval_test";
  fs::create_directories(dir);
  const std::string path = (dir / "grey.png").string();
  unsigned char grey[3] = {128, 128, 128};
  ASSERT_TRUE(OIIO::ImageBuf(OIIO::ImageSpec(1, 1, 3, OIIO::TypeDesc::UINT8), grey).write(path));
  ImageTexture srgb{path, true, TextureExtension::kRepeat, TextureInterpolation::kLinear};
  ImageTexture data = srgb;
  data.srgb = false;
  TextureSet set({srgb, data}, nullptr);
  float a[4], b[4];
  ASSERT_TRUE(set.lookup(0, Vec2(0.5f, 0.5f), a));
  ASSERT_TRUE(set.lookup(1, Vec2(0.5f, 0.5f), b));
  EXPECT_NEAR(a[0], 0.2158f, 2e-3f);
  EXPECT_NEAR(b[0], 128.0f / 255.0f, 2e-3f);
  EXPECT_NEAR(a[3], 1.0f, 1e-6f);  // no alpha channel: opaque
}

TEST_F(Textures, ExtensionModesAndMissingFiles) {
  ImageTexture repeat;
  repeat.path = write_quad_png("quad.png");
  repeat.interpolation = TextureInterpolation::kClosest;
  ImageTexture clip = repeat;
  clip.extension = TextureExtension::kClip;
  ImageTexture extend = repeat;
  extend.extension = TextureExtension::kExtend;
  ImageTexture missing = repeat;
  missing.path = "/nonexistent/photon/missing.png";
  std::vector<std::string> warnings;
  TextureSet set({repeat, clip, extend, missing}, &warnings);
  float rgba[4];
  ASSERT_TRUE(set.lookup(0, Vec2(1.25f, 1.75f), rgba));  // wraps to the top-left red texel
  EXPECT_NEAR(rgba[0], 1.0f, 1e-3f);
  EXPECT_NEAR(rgba[1], 0.0f, 1e-3f);
  ASSERT_TRUE(set.lookup(1, Vec2(1.25f, 1.75f), rgba));  // outside: transparent black
  EXPECT_NEAR(rgba[0] + rgba[1] + rgba[2] + rgba[3], 0.0f, 1e-4f);
  ASSERT_TRUE(set.lookup(2, Vec2(1.25f, 1.75f), rgba));  // clamped to the top-right green texel
  EXPECT_NEAR(rgba[1], 1.0f, 1e-3f);
  EXPECT_FALSE(set.valid(3));
  EXPECT_FALSE(set.lookup(3, Vec2(0.5f, 0.5f), rgba));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("missing.png"), std::string::npos);
  EXPECT_FALSE(set.lookup(0, Vec2(NAN, 0.5f), rgba));
}

// One quad at z = 0 facing +z with UVs, using material 0, to shade.
struct ShadeFixture {
  explicit ShadeFixture(Material m) {
    scene.materials.push_back(std::move(m));
    add_mesh_instance(&scene, make_textured_quad(), 0);
    accel = std::make_unique<Accel>(scene, nullptr);
  }
  SurfaceInteraction at(float x, float y) const {
    Ray ray;
    ray.origin = Vec3(x, y, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    Hit hit;
    EXPECT_TRUE(accel->intersect(ray, kVisibleAll, &hit));
    return accel->interaction(hit);
  }
  Scene scene;
  std::unique_ptr<Accel> accel;
};

TEST(MaterialEval, PrincipledMetalIsOneSchlickLobeOfTheBaseColour) {
  Closure c;
  c.type = ClosureType::kPrincipled;
  c[Param::kColor] = Input::constant(Vec3(1.0f, 0.766f, 0.336f));
  c[Param::kMetallic] = Input::constant(1.0f);
  c[Param::kRoughness] = Input::constant(0.25f);
  ShadeFixture f(Material{"gold", {c}});
  const ShadingPoint sp = shade_surface(f.at(0.1f, 0.2f), Vec3(0, 0, 1), *f.accel, nullptr);
  ASSERT_EQ(sp.bsdf.lobe_count(), 1);
  const Lobe& l = sp.bsdf.lobe(0);
  EXPECT_EQ(l.type, LobeType::kGgxReflection);
  EXPECT_EQ(l.fresnel, FresnelMode::kSchlick);
  EXPECT_NEAR(l.alpha, 0.0625f, 1e-6f);
  EXPECT_TRUE(VecNear(l.f0, Vec3(1.0f, 0.766f, 0.336f), 1e-5f));
  EXPECT_TRUE(is_black(sp.bsdf.diffuse_reflectance()));
}

TEST(MaterialEval, PrincipledDefaultsSplitIntoDiffuseAndSpecular) {
  Closure c;
  c.type = ClosureType::kPrincipled;
  c[Param::kAlpha] = Input::constant(0.75f);
  c[Param::kEmission] = Input::constant(Vec3(1.0f, 0.5f, 0.0f));
  c[Param::kStrength] = Input::constant(2.0f);
  ShadeFixture f(Material{"plastic", {c}});
  const ShadingPoint sp = shade_surface(f.at(0.0f, 0.0f), Vec3(0, 0, 1), *f.accel, nullptr);
  // Transparent (1 - alpha), Burley diffuse and the specular layer, scaled by alpha.
  ASSERT_EQ(sp.bsdf.lobe_count(), 3);
  EXPECT_EQ(sp.bsdf.lobe(0).type, LobeType::kTransparent);
  EXPECT_NEAR(sp.bsdf.lobe(0).weight.x, 0.25f, 1e-6f);
  EXPECT_TRUE(VecNear(sp.bsdf.diffuse_reflectance(), Vec3(0.8f * 0.75f), 1e-5f));
  EXPECT_TRUE(VecNear(sp.bsdf.lobe(2).f0, Vec3(0.04f), 1e-6f));       // 0.08 x specular 0.5
  EXPECT_TRUE(VecNear(sp.emission, Vec3(1.5f, 0.75f, 0.0f), 1e-5f));  // emission x alpha
}

TEST(MaterialEval, MixWeightsComeFromATextureAndBackFacesFlip) {
  ImageTexture tex;
  tex.path = write_quad_png("quad.png");
  tex.interpolation = TextureInterpolation::kClosest;
  Closure diffuse;
  diffuse.type = ClosureType::kDiffuse;
  diffuse[Param::kColor] = Input::constant(Vec3(0.5f));
  Closure glossy = Material::mirror(Vec3(1.0f)).closures[0];
  Input fac;
  fac.texture = 0;
  fac.channel = TextureChannel::kAlpha;
  diffuse.weight = {{fac, true}};  // Mix Shader: first input gets 1 - fac
  glossy.weight = {{fac, false}};
  ShadeFixture f(Material{"mix", {diffuse, glossy}});
  f.scene.textures.push_back(tex);
  TextureSet textures(f.scene.textures, nullptr);
  // Bottom-right texel: alpha 128/255, so diffuse weight ~0.498.
  const SurfaceInteraction si = f.at(0.5f, -0.5f);
  const ShadingPoint sp = shade_surface(si, Vec3(0, 0, 1), *f.accel, &textures);
  ASSERT_EQ(sp.bsdf.lobe_count(), 2);
  EXPECT_NEAR(sp.bsdf.diffuse_reflectance().x, 0.5f * (1.0f - 128.0f / 255.0f), 2e-3f);
  // Top-left texel: alpha 1, all glossy.
  const ShadingPoint top = shade_surface(f.at(-0.5f, 0.5f), Vec3(0, 0, 1), *f.accel, &textures);
  EXPECT_TRUE(is_black(top.bsdf.diffuse_reflectance()));
  // Seen from below, the shading frame faces the viewer and the face is not the front one.
  const ShadingPoint below = shade_surface(si, Vec3(0, 0, -1), *f.accel, &textures);
  EXPECT_FALSE(below.bsdf.front_facing());
  EXPECT_LT(below.bsdf.frame().n.z, 0.0f);
}

TEST(MaterialEval, TangentSpaceNormalMapBendsTheShadingNormal) {
  // A 1 x 1 normal map pointing halfway to +u: colour (0.5 + 0.5 sin, 0.5, 0.5 + 0.5 cos).
  const fs::path dir = fs::temp_directory_path() / "photon_material_eval_test";
  fs::create_directories(dir);
  const std::string path = (dir / "normal.exr").string();
  const float s = std::sin(0.5f), c = std::cos(0.5f);
  float px[3] = {0.5f + 0.5f * s, 0.5f, 0.5f + 0.5f * c};
  ASSERT_TRUE(OIIO::ImageBuf(OIIO::ImageSpec(1, 1, 3, OIIO::TypeDesc::FLOAT), px).write(path));
  Closure diffuse = Material::diffuse(Vec3(0.5f)).closures[0];
  diffuse.normal.texture = 0;
  diffuse.normal.strength = 1.0f;
  ShadeFixture f(Material{"bumpy", {diffuse}});
  f.scene.textures.push_back(
      {path, false, TextureExtension::kRepeat, TextureInterpolation::kLinear});
  TextureSet textures(f.scene.textures, nullptr);
  const ShadingPoint sp = shade_surface(f.at(0.2f, 0.3f), Vec3(0, 0, 1), *f.accel, &textures);
  // u runs along +x on this quad, so the normal tilts towards +x by 0.5 rad.
  EXPECT_TRUE(VecNear(sp.bsdf.frame().n, Vec3(s, 0.0f, c), 2e-3f));
  diffuse.normal.strength = 0.0f;  // strength 0: the interpolated normal
  ShadeFixture g(Material{"flat", {diffuse}});
  const ShadingPoint flat = shade_surface(g.at(0.2f, 0.3f), Vec3(0, 0, 1), *g.accel, &textures);
  EXPECT_TRUE(VecNear(flat.bsdf.frame().n, Vec3(0, 0, 1), 1e-6f));
}

TEST(MaterialEval, EmptyMaterialIsBlackAndMayBeSpecularIsConservative) {
  ShadeFixture f(Material{"empty", {}});
  const ShadingPoint sp = shade_surface(f.at(0.0f, 0.0f), Vec3(0, 0, 1), *f.accel, nullptr);
  EXPECT_TRUE(sp.bsdf.empty());
  EXPECT_TRUE(is_black(sp.emission));
  EXPECT_TRUE(Material::glass(1.5f).may_be_specular());
  EXPECT_TRUE(Material::mirror(Vec3(1.0f)).may_be_specular());
  EXPECT_FALSE(Material::diffuse(Vec3(0.5f)).may_be_specular());
  Closure rough = Material::mirror(Vec3(1.0f)).closures[0];
  rough.sharp = false;
  rough[Param::kRoughness] = Input::constant(0.4f);
  EXPECT_FALSE((Material{"rough", {rough}}).may_be_specular());
  EXPECT_TRUE(Material::emission(Vec3(1.0f)).may_emit());
  EXPECT_FALSE(Material::diffuse(Vec3(1.0f)).may_emit());
}

}  // namespace
}  // namespace material_eval_test
}  // namespace photon

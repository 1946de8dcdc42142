// The one table of material inputs (material_params.h) against what the core does with inputs:
// sanitize_material for constants and the lookups of material_eval.cpp for textures.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>

#include "photon/render/accel.h"
#include "photon/render/material_eval.h"
#include "photon/scene/material_params.h"
#include "photon/shading/textures.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace material_table_test {
namespace {

namespace fs = std::filesystem;

Material one_closure(ClosureType type, Param p, const Input& in) {
  Closure c;
  c.type = type;
  c.params = default_params(type);
  c[p] = in;
  return Material{"m", {c}};
}

TEST(MaterialTable, ClosureTypesInOrderAndEveryParamOnce) {
  const auto& specs = closure_specs();
  ASSERT_EQ(specs.size(), static_cast<size_t>(ClosureType::kVelvet) + 1);
  for (size_t i = 0; i < specs.size(); ++i) {
    EXPECT_EQ(static_cast<size_t>(specs[i].type), i) << specs[i].name;
    EXPECT_EQ(find_closure(specs[i].name), &specs[i]);
    std::set<Param> seen;
    for (const ClosureParamSpec& p : specs[i].params) {
      EXPECT_TRUE(seen.insert(p.param).second) << specs[i].name << " " << p.key;
      EXPECT_LE(p.range.lo, p.default_value) << specs[i].name << " " << p.key;
      EXPECT_LE(p.default_value, p.range.hi) << specs[i].name << " " << p.key;
      // One dict key per Param, whichever closure reads it.
      ASSERT_NE(find_param(p.key), nullptr) << p.key;
      EXPECT_EQ(find_param(p.key)->param, p.param) << p.key;
      EXPECT_EQ(&param_spec(specs[i].type, p.param), &p);
    }
  }
  // The two Principled BSDFs together read every Param (the fallback of the other closures)
  // but Velvet's Sigma; some closure reads each.
  std::set<Param> principled, any;
  for (ClosureType t : {ClosureType::kPrincipled, ClosureType::kPrincipledV2})
    for (const ClosureParamSpec& p : closure_spec(t).params) principled.insert(p.param);
  for (const ClosureSpec& c : specs)
    for (const ClosureParamSpec& p : c.params) any.insert(p.param);
  EXPECT_EQ(principled.size() + 1, static_cast<size_t>(Param::kCount));
  EXPECT_EQ(principled.count(Param::kSigma), 0u);
  EXPECT_EQ(any.size(), static_cast<size_t>(Param::kCount));
  EXPECT_EQ(find_closure("NO_SUCH_CLOSURE"), nullptr);
  EXPECT_EQ(find_param("no_such_param"), nullptr);
}

// Every entry: constants above the range end at its top, below it at its bottom, non-finite
// ones at the node's default, values inside it unchanged; param_range agrees with the table.
TEST(MaterialTable, SanitizeClampsEveryEntryToItsRange) {
  for (const ClosureSpec& closure : closure_specs())
    for (const ClosureParamSpec& spec : closure.params) {
      const std::string what = std::string(closure.name) + " " + spec.key;
      const ParamRange r = param_range(closure.type, spec.param);
      EXPECT_EQ(r.lo, spec.range.lo) << what;
      EXPECT_EQ(r.hi, spec.range.hi) << what;
      const float mid = 0.5f * (spec.range.lo + std::min(spec.range.hi, 10.0f));
      const struct {
        Vec3 in;
        Vec3 out;
      } cases[] = {
          {Vec3(2.0f * r.hi + 1.0f), Vec3(r.hi)},
          {Vec3(r.lo - 1.0f), Vec3(r.lo)},
          {Vec3(-INFINITY), Vec3(spec.default_value)},
          {Vec3(NAN), Vec3(spec.default_value)},
          {Vec3(mid, r.hi * 4.0f, NAN), Vec3(mid, r.hi, spec.default_value)},
      };
      for (const auto& c : cases) {
        Material m = one_closure(closure.type, spec.param, Input::constant(c.in));
        sanitize_material(&m, 0);
        const Vec3 got = m.closures[0][spec.param].value;
        EXPECT_EQ(got.x, c.out.x) << what << " in " << c.in.x;
        EXPECT_EQ(got.y, c.out.y) << what << " in " << c.in.y;
        EXPECT_EQ(got.z, c.out.z) << what << " in " << c.in.z;
      }
    }
}

// A texture index with no texture falls back to the node's own default (a Glass BSDF's white,
// not the Principled BSDF's grey).
TEST(MaterialTable, MissingTextureFallsBackToTheNodesDefault) {
  for (const ClosureSpec& closure : closure_specs())
    for (const ClosureParamSpec& spec : closure.params) {
      Input in;
      in.texture = 3;
      Material m = one_closure(closure.type, spec.param, in);
      sanitize_material(&m, 1);
      EXPECT_EQ(m.closures[0][spec.param].texture, -1);
      EXPECT_EQ(m.closures[0][spec.param].value.x, spec.default_value)
          << closure.name << " " << spec.key;
    }
}

// One quad at z = 0 facing +z with UVs in [0, 1], using material 0.
struct Quad {
  explicit Quad(Material m) {
    scene.materials.push_back(std::move(m));
    add_mesh_instance(&scene, make_textured_quad(), 0);
    accel = std::make_unique<Accel>(scene, nullptr);
  }
  ShadingPoint shade(const TextureSet* textures) const {
    Ray ray;
    ray.origin = Vec3(0.1f, 0.2f, 1.0f);
    ray.direction = Vec3(0, 0, -1);
    Hit hit;
    EXPECT_TRUE(accel->intersect(ray, kVisibleAll, &hit));
    return shade_surface(accel->interaction(hit), Vec3(0, 0, 1), *accel, textures);
  }
  Scene scene;
  std::unique_ptr<Accel> accel;
};

std::string grey_exr(float v) {
  const fs::path dir = fs::temp_directory_path() / "photon_material_table_test";
  fs::create_directories(dir);
  const std::string path = (dir / ("grey_" + std::to_string(v) + ".exr")).string();
  float px[4] = {v, v, v, v};
  EXPECT_TRUE(OIIO::ImageBuf(OIIO::ImageSpec(1, 1, 4, OIIO::TypeDesc::FLOAT), px).write(path));
  return path;
}

void expect_same(const ShadingPoint& a, const ShadingPoint& b, const std::string& what) {
  EXPECT_EQ(a.emission.x, b.emission.x) << what;
  EXPECT_EQ(a.holdout, b.holdout) << what;
  ASSERT_EQ(a.bsdf.lobe_count(), b.bsdf.lobe_count()) << what;
  for (int i = 0; i < a.bsdf.lobe_count(); ++i) {
    const Lobe &la = a.bsdf.lobe(i), &lb = b.bsdf.lobe(i);
    EXPECT_EQ(la.type, lb.type) << what << " lobe " << i;
    EXPECT_EQ(la.weight.x, lb.weight.x) << what << " lobe " << i;
    EXPECT_EQ(la.alpha, lb.alpha) << what << " lobe " << i;
    EXPECT_EQ(la.roughness, lb.roughness) << what << " lobe " << i;
    EXPECT_EQ(la.ior, lb.ior) << what << " lobe " << i;
    EXPECT_EQ(la.f0.x, lb.f0.x) << what << " lobe " << i;
  }
}

// A texture above an input's range shades exactly like the constant sanitize_material clamps:
// both read the same range (textures clamp after each lookup).
TEST(MaterialTable, TexturesAboveTheRangeShadeLikeClampedConstants) {
  setenv("PHOTON_TEXTURE_CACHE",
         (fs::temp_directory_path() / "photon_material_table_cache").c_str(), 1);
  for (const ClosureSpec& closure : closure_specs())
    for (const ClosureParamSpec& spec : closure.params) {
      const std::string what = std::string(closure.name) + " " + spec.key;
      const float above = 2.0f * spec.range.hi;
      Material constant = one_closure(closure.type, spec.param, Input::constant(above));
      sanitize_material(&constant, 0);
      Input textured;
      textured.texture = 0;
      Material mapped = one_closure(closure.type, spec.param, textured);
      Quad a(constant), b(mapped);
      b.scene.textures.push_back(
          {grey_exr(above), false, TextureExtension::kRepeat, TextureInterpolation::kClosest});
      std::vector<std::string> warnings;
      TextureSet textures(b.scene.textures, &warnings);
      ASSERT_TRUE(textures.valid(0)) << what;
      expect_same(a.shade(nullptr), b.shade(&textures), what);
    }
}

}  // namespace
}  // namespace material_table_test
}  // namespace photon

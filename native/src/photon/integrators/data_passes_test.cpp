// The data passes (data_passes.h) from a render session: values at known first hits, Cycles'
// first-sample and averaged semantics, the background's values, and independence from tiles
// and threads.
#include "photon/integrators/data_passes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "photon/scene/material_params.h"
#include "photon/session/render_session.h"
#include "photon/shading/program_eval.h"
#include "photon/testing/test_scenes.h"

namespace photon {
namespace data_passes_test {
namespace {

constexpr float kCameraHeight = 3.0f;
constexpr float kObjectIndex = 4.0f, kMaterialIndex = 6.0f;

// The textured quad [-1, 1]^2 at z = 0 (UVs (x + 1) / 2, (y + 1) / 2) seen from straight above
// by a camera at height 3 with a 1 x 1 window at distance 1: the quad covers the middle two
// thirds of the image, the background the rest.
std::shared_ptr<const Scene> quad_scene(Projection projection = Projection::kPerspective) {
  auto scene = std::make_shared<Scene>();
  Material m = Material::diffuse(Vec3(0.5f), "grey");
  m.pass_index = kMaterialIndex;
  scene->materials.push_back(m);
  add_mesh_instance(scene.get(), make_textured_quad(), 0);
  scene->instances[0].pass_index = kObjectIndex;
  scene->camera.projection = projection;
  scene->camera.set_camera_to_world(Transform::translation(Vec3(0.0f, 0.0f, kCameraHeight)));
  if (projection == Projection::kOrthographic) {
    scene->camera.window_min_x = scene->camera.window_min_y = -1.5f;
    scene->camera.window_max_x = scene->camera.window_max_y = 1.5f;
  }
  scene->world = World::uniform(Vec3(0.1f));
  return scene;
}

RenderSettings settings(int size, int spp, uint32_t mask) {
  RenderSettings s;
  s.full_width = s.full_height = size;
  s.x0 = s.y0 = 0;
  s.x1 = s.y1 = size;
  s.samples = spp;
  s.seed = 5;
  s.integrator = IntegratorType::kRayTrace;
  s.data_passes.mask = mask;
  s.data_passes.mist_start = 1.0f;
  s.data_passes.mist_depth = 4.0f;
  s.data_passes.mist_falloff = 2.0f;
  return s;
}

struct Frame {
  std::vector<float> rgba, data;
  int floats = 0, width = 0;
  const float* pass(int x, int y, uint32_t mask, uint32_t bit) const {
    return &data[(static_cast<size_t>(y) * width + x) * floats + data_pass_offset(mask, bit)];
  }
};

// Renders and assembles the tiles' data passes into one frame.
Frame render(std::shared_ptr<const Scene> scene, const RenderSettings& s) {
  RenderSession session(std::move(scene), s);
  session.start();
  Frame f;
  f.width = s.full_width;
  f.floats = data_pass_pixel_floats(s.data_passes);
  f.data.assign(static_cast<size_t>(s.full_width) * s.full_height * f.floats, -1.0f);
  while (true) {
    const bool done = session.finished();
    for (const Tile& t : session.take_tiles(0.05)) {
      // Every pass the settings ask for, by name, and no other.
      const std::vector<DataPassSlot> slots = data_pass_slots(s.data_passes);
      EXPECT_EQ(t.passes.size(), slots.size());
      for (const DataPassSlot& slot : slots) {
        const PassImage* pass = t.pass(slot.name);
        EXPECT_NE(pass, nullptr) << slot.name;
        if (!pass) continue;
        EXPECT_EQ(pass->pixels.size(), static_cast<size_t>(t.width) * t.height * slot.channels);
        for (int row = 0; row < t.height; ++row)
          for (int col = 0; col < t.width; ++col)
            std::copy_n(&pass->pixels[(static_cast<size_t>(row) * t.width + col) * slot.channels],
                        slot.channels,
                        &f.data[(static_cast<size_t>(t.y + row) * f.width + t.x + col) * f.floats +
                                slot.offset]);
      }
    }
    if (done) break;
  }
  session.wait();
  f.rgba = session.image();
  return f;
}

TEST(DataPasses, LayoutFollowsTheTable) {
  EXPECT_EQ(data_pass_floats(kPassAllData), 1 + 1 + 3 + 3 + 3 + 1 + 1 + 4 * 3 + 3 + 3 + 1);
  EXPECT_EQ(data_pass_floats(0), 0);
  const uint32_t mask = kPassMist | kPassUv | kPassMaterialIndex;
  EXPECT_EQ(data_pass_offset(mask, kPassMist), 0);
  EXPECT_EQ(data_pass_offset(mask, kPassUv), 1);
  EXPECT_EQ(data_pass_offset(mask, kPassMaterialIndex), 4);
  EXPECT_EQ(data_pass_offset(mask, kPassDepth), -1);
}

float expected_mist(float distance) {
  const float m = std::clamp((distance - 1.0f) / 4.0f, 0.0f, 1.0f);
  return m * m;  // quadratic falloff; 1 - (1 - m) for an opaque hit
}

void check_quad_pixels(const Frame& f, int size, bool orthographic) {
  int quad = 0, background = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float* pos = f.pass(x, y, kPassAllData, kPassPosition);
      const float depth = *f.pass(x, y, kPassAllData, kPassDepth);
      const float* n = f.pass(x, y, kPassAllData, kPassNormal);
      const float* uv = f.pass(x, y, kPassAllData, kPassUv);
      const float mist = *f.pass(x, y, kPassAllData, kPassMist);
      const float ob = *f.pass(x, y, kPassAllData, kPassObjectIndex);
      const float ma = *f.pass(x, y, kPassAllData, kPassMaterialIndex);
      // Pixels fully inside or outside the quad (one sample: the pixel centre +- half a pixel).
      const bool inside = depth < 1e9f;
      if (inside) {
        ++quad;
        EXPECT_NEAR(pos[2], 0.0f, 1e-5f);
        EXPECT_LE(std::fabs(pos[0]), 1.0f + 1e-5f);
        EXPECT_NEAR(depth, kCameraHeight, 1e-5f);  // along the view axis: the plane's height
        EXPECT_NEAR(n[0], 0.0f, 1e-6f);
        EXPECT_NEAR(n[2], 1.0f, 1e-6f);
        EXPECT_NEAR(uv[0], 0.5f * (pos[0] + 1.0f), 1e-5f);
        EXPECT_NEAR(uv[1], 0.5f * (pos[1] + 1.0f), 1e-5f);
        EXPECT_EQ(uv[2], 1.0f);
        const float distance =
            orthographic
                ? kCameraHeight
                : std::sqrt(pos[0] * pos[0] + pos[1] * pos[1] + kCameraHeight * kCameraHeight);
        EXPECT_NEAR(mist, expected_mist(distance), 1e-5f);
        EXPECT_EQ(ob, kObjectIndex);
        EXPECT_EQ(ma, kMaterialIndex);
      } else {
        ++background;
        // Cycles' film: Depth 1e10 where nothing was hit, Mist 1, zeros elsewhere.
        EXPECT_EQ(depth, 1e10f);
        EXPECT_EQ(mist, 1.0f);
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(pos[c], 0.0f);
          EXPECT_EQ(n[c], 0.0f);
          EXPECT_EQ(uv[c], 0.0f);
        }
        EXPECT_EQ(ob, 0.0f);
        EXPECT_EQ(ma, 0.0f);
      }
    }
  EXPECT_GT(quad, size * size / 3);
  EXPECT_GT(background, size * size / 4);
}

TEST(DataPasses, PerspectiveQuadAndBackground) {
  const int size = 24;
  check_quad_pixels(render(quad_scene(), settings(size, 1, kPassAllData)), size, false);
}

TEST(DataPasses, OrthographicMistIsAlongTheViewAxis) {
  const int size = 24;
  check_quad_pixels(render(quad_scene(Projection::kOrthographic), settings(size, 1, kPassAllData)),
                    size, true);
}

// At the quad's edge the samples of a pixel split between quad and background: indices and
// depth come from the first sample (never a blend), normals are averaged (shorter than 1).
TEST(DataPasses, FirstSampleIndicesAveragedNormals) {
  const int size = 25;  // the quad's edges cut pixels (at 8.33 and 16.67)
  RenderSettings s = settings(size, 16, kPassAllData);
  s.transparent_background = true;  // alpha: the share of samples that hit the quad
  const Frame f = render(quad_scene(), s);
  int split = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float ob = *f.pass(x, y, kPassAllData, kPassObjectIndex);
      const float depth = *f.pass(x, y, kPassAllData, kPassDepth);
      EXPECT_TRUE(ob == 0.0f || ob == kObjectIndex) << ob;
      EXPECT_TRUE(depth == 1e10f || std::fabs(depth - kCameraHeight) < 1e-5f) << depth;
      const float nz = f.pass(x, y, kPassAllData, kPassNormal)[2];
      if (nz > 0.01f && nz < 0.99f) {
        ++split;
        // The pixel's alpha is the share of samples that hit the quad: so is the normal's z.
        EXPECT_NEAR(nz, f.rgba[(static_cast<size_t>(y) * size + x) * 4 + 3], 1e-5f);
        const float mist = *f.pass(x, y, kPassAllData, kPassMist);
        EXPECT_GT(mist, 1.0f - nz);  // the background's samples count as full mist
      }
    }
  EXPECT_GT(split, 8);  // the edge pixels
}

TEST(DataPasses, IndependentOfTilesAndThreads) {
  RenderSettings a = settings(40, 4, kPassAllData), b = a;
  a.tile_size = 8;
  a.threads = 1;
  b.tile_size = 32;
  b.threads = 3;
  const Frame fa = render(quad_scene(), a), fb = render(quad_scene(), b);
  EXPECT_EQ(fa.data, fb.data);
}

TEST(DataPasses, CombinedUnchangedByDataPasses) {
  const Frame with = render(quad_scene(), settings(24, 4, kPassAllData));
  const Frame without = render(quad_scene(), settings(24, 4, 0));
  EXPECT_EQ(with.rgba, without.rgba);
  EXPECT_TRUE(without.data.empty());
}

TEST(DataPasses, PositionAddsTheOriginOffset) {
  RenderSettings s = settings(16, 1, kPassPosition | kPassDepth);
  s.data_passes.origin = Vec3(1000.0f, -2000.0f, 500.0f);
  const Frame f = render(quad_scene(), s);
  const uint32_t mask = s.data_passes.mask;
  const float* pos = f.pass(8, 8, mask, kPassPosition);
  EXPECT_NEAR(pos[2], 500.0f, 1e-3f);
  EXPECT_NEAR(pos[0], 1000.0f, 1.0f);
  EXPECT_NEAR(pos[1], -2000.0f, 1.0f);
}

// A fully transparent quad (Transparent BSDF) 1 m above the opaque one: with the default alpha
// threshold the single-sample passes see through it to the opaque quad, and so does Mist
// (the transparent surface adds nothing); with threshold 0 they stop at the first hit.
std::shared_ptr<const Scene> veiled_quad_scene() {
  auto scene = std::make_shared<Scene>(*quad_scene());
  Closure c;
  c.type = ClosureType::kTransparent;
  c.params = default_params(ClosureType::kTransparent);
  c[Param::kColor] = Input::constant(Vec3(1.0f));
  Material veil;
  veil.name = "veil";
  veil.closures.push_back(c);
  veil.pass_index = 8.0f;
  scene->materials.push_back(veil);
  add_mesh_instance(scene.get(), make_textured_quad(), 1,
                    Transform::translation(Vec3(0.0f, 0.0f, 1.0f)));
  scene->instances[1].pass_index = 9.0f;
  return scene;
}

TEST(DataPasses, AlphaThresholdSeesThroughTransparentSurfaces) {
  const int size = 24;
  RenderSettings s = settings(size, 1, kPassAllData);
  const Frame through = render(veiled_quad_scene(), s);
  s.data_passes.alpha_threshold = 0.0f;
  const Frame first = render(veiled_quad_scene(), s);
  const int c = size / 2;
  EXPECT_EQ(*through.pass(c, c, kPassAllData, kPassObjectIndex), kObjectIndex);
  EXPECT_EQ(*through.pass(c, c, kPassAllData, kPassMaterialIndex), kMaterialIndex);
  EXPECT_NEAR(*through.pass(c, c, kPassAllData, kPassDepth), kCameraHeight, 1e-5f);
  EXPECT_EQ(*first.pass(c, c, kPassAllData, kPassObjectIndex), 9.0f);
  EXPECT_EQ(*first.pass(c, c, kPassAllData, kPassMaterialIndex), 8.0f);
  EXPECT_NEAR(*first.pass(c, c, kPassAllData, kPassDepth), kCameraHeight - 1.0f, 1e-5f);
  // Mist and the diffuse colour come from the opaque quad behind the veil either way.
  const float* pos = through.pass(c, c, kPassAllData, kPassPosition);
  const float distance = std::sqrt(pos[0] * pos[0] + pos[1] * pos[1] + 9.0f);
  for (const Frame* f : {&through, &first}) {
    EXPECT_NEAR(*f->pass(c, c, kPassAllData, kPassMist), expected_mist(distance), 1e-5f);
    EXPECT_NEAR(f->pass(c, c, kPassAllData, kPassDiffuseColor)[0], 0.5f, 1e-6f);
  }
}

// The veiled quad with Cryptomatte IDs: the fully transparent veil takes no share of a sample
// (one minus its transparency is zero), the quad behind it all of it; the layers come after the
// data passes, ranked, and do not depend on tiles or threads.
TEST(DataPasses, CryptomatteCountsWhatTheSamplesSeeThroughTransparency) {
  auto scene = std::make_shared<Scene>(*veiled_quad_scene());
  const float quad_id = 3.5f, veil_id = 7.25f, asset_id = -2.0f, material_id = 1.5f;
  scene->instances[0].cryptomatte_object = quad_id;
  scene->instances[0].cryptomatte_asset = asset_id;
  scene->instances[1].cryptomatte_object = veil_id;
  scene->materials[0].cryptomatte_material = material_id;
  RenderSettings a = settings(24, 4, kPassDepth);
  a.data_passes.cryptomatte = kCryptoObject | kCryptoMaterial | kCryptoAsset;
  a.data_passes.cryptomatte_depth = 4;
  const std::vector<DataPassSlot> slots = data_pass_slots(a.data_passes);
  ASSERT_EQ(slots.size(), 1u + 3 * 2);
  EXPECT_EQ(slots[1].name, "CryptoObject00");
  EXPECT_EQ(slots[2].name, "CryptoObject01");
  EXPECT_EQ(slots[6].name, "CryptoAsset01");
  EXPECT_EQ(slots[3].offset, 1 + 2 * 4);
  RenderSettings b = a;
  a.tile_size = 8;
  a.threads = 1;
  b.tile_size = 32;
  b.threads = 3;
  const Frame fa = render(scene, a), fb = render(scene, b);
  EXPECT_EQ(fa.data, fb.data);
  const int c = 12;  // the middle pixel sees the quad through the veil
  const float* px = &fa.data[(static_cast<size_t>(c) * fa.width + c) * fa.floats];
  for (int kind = 0; kind < 3; ++kind) {
    const float* layer = px + slots[1 + 2 * kind].offset;
    const float expected_id = kind == 0 ? quad_id : kind == 1 ? material_id : asset_id;
    EXPECT_EQ(layer[0], expected_id) << slots[1 + 2 * kind].name;
    EXPECT_FLOAT_EQ(layer[1], 1.0f);
    EXPECT_EQ(layer[2], 0.0f);  // no second ID: the veil took no share
    EXPECT_EQ(layer[3], 0.0f);
  }
  // A corner pixel sees the background: no IDs at all.
  const float* corner = &fa.data[0];
  for (int f = 1; f < fa.floats; ++f) EXPECT_EQ(corner[f], 0.0f) << f;
}

// Shader AOVs on the veiled quad: the quad's AOV Output nodes write its position (through its
// program) as a colour and its x as a value, and a constant 2 into "flag", into which the veil
// writes 1 and the world 4. Each writes the pass of its name and kind only; the veil's and the
// quad's (or the world's) values add up while the veil is below the alpha threshold, as Cycles
// writes AOVs until the single-sample passes are done; a transparent film's world writes none.
TEST(DataPasses, ShaderAovsWriteUntilTheFirstOpaqueEnoughHit) {
  auto scene = std::make_shared<Scene>(*veiled_quad_scene());
  Material& quad = scene->materials[0];
  NodeDesc geometry;
  geometry.type = "ShaderNodeNewGeometry";
  geometry.outputs = {{"Position", 0}};
  quad.program.registers.assign(3, 0.0f);
  std::string error;
  ASSERT_EQ(compile_node(geometry, &quad.program, &error), CompileStatus::kCompiled) << error;
  Input position;
  position.reg = 0;
  quad.aovs = {{"pos", true, position},
               {"px", false, position},
               {"flag", false, Input::constant(2.0f)},
               {"pos", false, Input::constant(5.0f)}};  // a value AOV: no "pos" value pass
  scene->materials[1].aovs = {{"flag", false, Input::constant(1.0f)}};
  scene->world.aovs = {{"flag", false, Input::constant(4.0f)}};

  RenderSettings s = settings(24, 1, kPassPosition);
  s.data_passes.aovs = {{"pos", true}, {"px", false}, {"flag", false}, {"none", true}};
  const std::vector<DataPassSlot> slots = data_pass_slots(s.data_passes);
  ASSERT_EQ(slots.size(), 5u);
  EXPECT_EQ(slots[1].name, "pos");
  EXPECT_EQ(slots[1].channel_ids, "RGBA");
  EXPECT_EQ(slots[2].channel_ids, "X");
  EXPECT_EQ(slots[4].offset, 3 + 4 + 1 + 1);
  RenderSettings other = s;
  other.tile_size = 7;
  other.threads = 3;
  const Frame through = render(scene, s);
  EXPECT_EQ(through.data, render(scene, other).data);
  s.data_passes.alpha_threshold = 0.0f;
  const Frame first = render(scene, s);

  const int c = 12;
  const auto at = [&](const Frame& f, int x, int y, int slot) {
    return &f.data[(static_cast<size_t>(y) * f.width + x) * f.floats + slots[slot].offset];
  };
  const float* p = through.pass(c, c, kPassPosition, kPassPosition);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(at(through, c, c, 1)[k], p[k]);
  EXPECT_EQ(at(through, c, c, 1)[3], 1.0f);
  EXPECT_EQ(*at(through, c, c, 2), p[0]);
  EXPECT_EQ(*at(through, c, c, 3), 3.0f);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(at(through, c, c, 4)[k], 0.0f);
  // Threshold 0: the veil is the first hit, and only its AOV is written.
  for (int k = 0; k < 4; ++k) EXPECT_EQ(at(first, c, c, 1)[k], 0.0f);
  EXPECT_EQ(*at(first, c, c, 3), 1.0f);
  // A corner sees the veil (it covers the image) and the world behind it.
  for (int f = 3; f < through.floats; ++f)
    EXPECT_EQ(through.data[f], f == slots[3].offset ? 5.0f : 0.0f) << f;
  s.data_passes.alpha_threshold = 0.5f;
  s.transparent_background = true;
  const Frame transparent = render(scene, s);
  EXPECT_EQ(transparent.data[slots[3].offset], 1.0f);
  EXPECT_EQ(*at(transparent, c, c, 3), 3.0f);
}

// SPPM and VCM trace their own camera paths per iteration; their data passes come from the camera
// rays of the Sampling panel's samples, so they are the same floats as a tiled render's, for any
// thread count, and every published iteration carries them.
TEST(DataPasses, SppmAndVcmWriteTheTiledIntegratorsDataPasses) {
  auto scene = std::make_shared<Scene>(*veiled_quad_scene());
  scene->instances[0].cryptomatte_object = 3.5f;
  scene->instances[1].cryptomatte_object = 7.25f;
  RenderSettings tiled = settings(24, 4, kPassAllData);
  tiled.data_passes.cryptomatte = kCryptoObject;
  tiled.data_passes.cryptomatte_depth = 2;
  const Frame expected = render(scene, tiled);
  for (IntegratorType type : {IntegratorType::kSppm, IntegratorType::kVcm}) {
    RenderSettings iterative = tiled;
    iterative.integrator = type;
    iterative.sppm_iterations = 2;
    iterative.vcm_iterations = 2;
    iterative.sppm_photons_per_iteration = 2000;
    iterative.vcm_light_paths = 2000;
    iterative.threads = 1;
    RenderSettings more_threads = iterative;
    more_threads.threads = 3;
    const Frame one = render(scene, iterative), three = render(scene, more_threads);
    EXPECT_EQ(one.data, expected.data) << static_cast<int>(type);
    EXPECT_EQ(three.data, expected.data) << static_cast<int>(type);
  }
}

}  // namespace
}  // namespace data_passes_test
}  // namespace photon

#include "photon/shading/textures.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "photon/render/material_eval.h"
#include "photon/session/scene_resources.h"
#include "photon/shading/texture_convert.h"
#include "photon/testing/test_scenes.h"
#include "photon/testing/timing_slack.h"

namespace photon {
namespace textures_test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Each test gets an empty texture cache of its own.
struct TextureCache : ::testing::Test {
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() / ("photon_textures_test_" + std::string(info->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    setenv("PHOTON_TEXTURE_CACHE", (dir / "cache").c_str(), 1);
  }
  void TearDown() override { fs::remove_all(dir); }

  // A `size` x `size` float RGB(A) EXR filled with `value`.
  std::string write_exr(const std::string& name, float value, int size = 4, int channels = 3) {
    std::vector<float> px(static_cast<size_t>(size) * size * channels, value);
    const std::string path = (dir / name).string();
    // Uncompressed: the file's size does not depend on its values.
    OIIO::ImageSpec spec(size, size, channels, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "none");
    EXPECT_TRUE(OIIO::ImageBuf(spec, px.data()).write(path));
    return path;
  }
  std::vector<fs::path> cached_files() const {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir / "cache"))
      if (e.path().extension() == ".exr") files.push_back(e.path());
    return files;
  }
  fs::path dir;
};

TEST_F(TextureCache, FloatTexturesKeepValuesBeyondHalfRange) {
  // Half floats end at 65504: an emission texture of 1e6 must stay 1e6.
  ImageTexture tex{write_exr("bright.exr", 1e6f), false, TextureExtension::kRepeat,
                   TextureInterpolation::kLinear};
  auto pixels = std::make_shared<TexturePixels>(8, 8, true);
  std::fill(pixels->data(), pixels->data() + 8 * 8 * 4, 2e6f);
  ImageTexture generated{"generated", false, TextureExtension::kRepeat,
                         TextureInterpolation::kLinear, pixels};
  std::vector<std::string> warnings;
  TextureSet set({tex, generated}, &warnings);
  ASSERT_TRUE(warnings.empty()) << warnings.front();
  float rgba[4];
  ASSERT_TRUE(set.lookup(0, Vec2(0.3f, 0.6f), rgba));
  EXPECT_FLOAT_EQ(rgba[0], 1e6f);
  EXPECT_FLOAT_EQ(set.max_color(0), 1e6f);
  ASSERT_TRUE(set.lookup(1, Vec2(0.3f, 0.6f), rgba));
  EXPECT_FLOAT_EQ(rgba[2], 2e6f);
}

TEST_F(TextureCache, GeneratedPixelsAreReadBottomRowFirst) {
  // Blender stores generated images bottom row first; v runs up in both.
  auto pixels = std::make_shared<TexturePixels>(2, 2, true);
  float* p = pixels->data();
  for (int i = 0; i < 16; ++i) p[i] = 0.0f;
  p[0] = 1.0f;          // bottom-left red
  p[3 * 4 + 2] = 1.0f;  // top-right blue
  ImageTexture tex{"quad", false, TextureExtension::kRepeat, TextureInterpolation::kClosest,
                   pixels};
  TextureSet set({tex}, nullptr);
  float rgba[4];
  ASSERT_TRUE(set.lookup(0, Vec2(0.25f, 0.25f), rgba));
  EXPECT_FLOAT_EQ(rgba[0], 1.0f);
  ASSERT_TRUE(set.lookup(0, Vec2(0.75f, 0.75f), rgba));
  EXPECT_FLOAT_EQ(rgba[2], 1.0f);
}

TEST_F(TextureCache, SameContentReusesTheFileAndChangedContentDoesNot) {
  const std::string path = write_exr("a.exr", 0.25f);
  ImageTexture tex{path, false, TextureExtension::kRepeat, TextureInterpolation::kLinear};
  {
    TextureSet first({tex}, nullptr);
    EXPECT_EQ(first.reused(), 0u);
  }
  auto files = cached_files();
  ASSERT_EQ(files.size(), 1u);
  struct stat before {};
  ASSERT_EQ(::stat(files[0].c_str(), &before), 0);
  {
    TextureSet second({tex}, nullptr);  // not converted again: the same file (same inode)
    EXPECT_EQ(second.reused(), 1u);
    struct stat after {};
    ASSERT_EQ(::stat(files[0].c_str(), &after), 0);
    EXPECT_EQ(before.st_ino, after.st_ino);
  }
  // New content of the same size with the old modification time: a new file and new values
  // (a key of path, size and time would render the stale texture).
  const auto mtime = fs::last_write_time(path);
  const auto size = fs::file_size(path);
  write_exr("a.exr", 0.75f);
  ASSERT_EQ(fs::file_size(path), size);
  fs::last_write_time(path, mtime);
  TextureSet third({tex}, nullptr);
  EXPECT_EQ(third.reused(), 0u);
  EXPECT_EQ(cached_files().size(), 2u);
  float rgba[4];
  ASSERT_TRUE(third.lookup(0, Vec2(0.5f, 0.5f), rgba));
  EXPECT_FLOAT_EQ(rgba[0], 0.75f);
}

TEST_F(TextureCache, LeastRecentlyUsedFilesAreEvictedAboveTheLimit) {
  std::vector<ImageTexture> textures;
  for (int i = 0; i < 3; ++i)
    textures.push_back({write_exr("t" + std::to_string(i) + ".exr", 0.1f * (i + 1), 256), false,
                        TextureExtension::kRepeat, TextureInterpolation::kLinear});
  for (int i = 0; i < 3; ++i) {
    TextureSet set({textures[i]}, nullptr);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // distinct use times
  }
  const uint64_t one = fs::file_size(cached_files()[0]);
  ASSERT_EQ(cached_files().size(), 3u);
  // Room for two files: the oldest (t0) goes when t2 is used again.
  setenv("PHOTON_TEXTURE_CACHE_MB", std::to_string((2.5 * one) / 1048576.0).c_str(), 1);
  { TextureSet again({textures[2]}, nullptr); }
  unsetenv("PHOTON_TEXTURE_CACHE_MB");
  EXPECT_EQ(cached_files().size(), 2u);
  TextureSet check({textures[0]}, nullptr);
  EXPECT_EQ(check.reused(), 0u);  // t0 was evicted
}

TEST_F(TextureCache, CancelStopsConversionWithin100Milliseconds) {
  // 4096^2 float RGBA (256 MB) takes seconds to convert on this machine.
  auto pixels = std::make_shared<TexturePixels>(4096, 4096, true);
  for (size_t i = 0; i < size_t(4096) * 4096 * 4; ++i) pixels->data()[i] = (i % 97) * 0.01f;
  ImageTexture tex{"big", true, TextureExtension::kRepeat, TextureInterpolation::kLinear, pixels};
  std::atomic<bool> cancel{false};
  Clock::time_point cancelled_at, returned_at;
  std::unique_ptr<TextureSet> set;
  std::thread worker([&] {
    set = std::make_unique<TextureSet>(std::vector<ImageTexture>{tex}, nullptr, &cancel);
    returned_at = Clock::now();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  cancelled_at = Clock::now();
  cancel = true;
  worker.join();
  EXPECT_TRUE(set->cancelled());
  EXPECT_FALSE(set->valid(0));
  const double ms = std::chrono::duration<double, std::milli>(returned_at - cancelled_at).count();
  EXPECT_LT(ms, 150.0 * timing_slack()) << "cancel took " << ms << " ms";
  EXPECT_TRUE(cached_files().empty());  // no half-written texture is left behind
}

TEST_F(TextureCache, TexturedInputsAreClampedToTheirRangeWithAWarning) {
  // Base Color 1000 would multiply every bounce's energy by 1000; emission keeps its value.
  Scene scene;
  scene.textures.push_back({write_exr("albedo.exr", 1000.0f), false, TextureExtension::kRepeat,
                            TextureInterpolation::kLinear});
  Closure principled;
  principled.type = ClosureType::kPrincipled;
  principled[Param::kColor].texture = 0;
  principled[Param::kEmission].texture = 0;
  principled[Param::kSpecular] = Input::constant(0.0f);
  scene.materials.push_back(Material{"hot", {principled}});
  add_mesh_instance(&scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 0);
  RenderSettings settings;
  std::vector<std::string> warnings;
  SceneResources resources(scene, settings, &warnings);
  int base_warnings = 0;
  for (const std::string& w : warnings) {
    EXPECT_EQ(w.find("Emission"), std::string::npos) << w;
    if (w.find("Base Color") != std::string::npos && w.find("clamped to 1") != std::string::npos)
      ++base_warnings;
  }
  EXPECT_EQ(base_warnings, 1);
  Ray ray;
  ray.origin = Vec3(0.1f, 0.2f, 1.0f);
  ray.direction = Vec3(0, 0, -1);
  Hit hit;
  ASSERT_TRUE(resources.accel().intersect(ray, kVisibleAll, &hit));
  const SurfaceInteraction si = resources.accel().interaction(hit);
  const ShadingPoint sp =
      shade_surface(si, Vec3(0, 0, 1), resources.accel(), &resources.textures());
  EXPECT_NEAR(sp.bsdf.diffuse_reflectance().x, 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(sp.emission.x, 1000.0f);
}

TEST_F(TextureCache, OneFileConvertedConcurrentlyAsColourAndAsDataConvertsRightBothTimes) {
  // Two image nodes on one file, one sRGB and one Non-Color, are two conversions of the same
  // source at once; the first to finish must not close the file under the other. The same
  // holds for a file that cannot be read: both fail cleanly.
  const std::string small = write_exr("small.exr", 0.5f, 4, 4);
  const std::string broken = (dir / "broken.png").string();
  std::ofstream(broken, std::ios::binary) << "\x89PNG\r\n\x1a\n not a png";
  for (int round = 0; round < 40; ++round) {
    const std::string cache = (dir / ("cache" + std::to_string(round))).string();
    const std::string& path = round % 2 ? broken : small;
    ConvertRequest requests[4] = {{path, nullptr, true},
                                  {path, nullptr, false},
                                  {path, nullptr, true},
                                  {path, nullptr, false}};
    ConvertedTexture out[4];
    std::string errors[4];
    bool ok[4] = {};
    std::vector<std::thread> threads;
    for (int i = 0; i < 4; ++i)
      threads.emplace_back([&, i] {
        // Distinct keys per thread, so every thread converts rather than reusing.
        ok[i] =
            convert_texture(requests[i], 1000 * round + i + 1, cache, nullptr, &out[i], &errors[i]);
      });
    for (std::thread& t : threads) t.join();
    for (int i = 0; i < 4; ++i) {
      if (path == broken) {
        EXPECT_FALSE(ok[i]);
        EXPECT_FALSE(errors[i].empty());
        continue;
      }
      ASSERT_TRUE(ok[i]) << "round " << round << " conversion " << i << ": " << errors[i];
      // 0.5 read as sRGB is 0.214 linear.
      EXPECT_NEAR(out[i].max_color, requests[i].srgb ? 0.21404f : 0.5f, 1e-5f)
          << "round " << round << " conversion " << i;
    }
  }
}

}  // namespace
}  // namespace textures_test
}  // namespace photon

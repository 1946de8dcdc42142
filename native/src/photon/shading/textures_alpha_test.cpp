// Image alpha as Cycles 3.4 loads and reads it (the image conformance manifest checks the same
// against Cycles renders, test_scenes/nodes/image.json): straight-alpha colour files stored
// premultiplied, 8-bit in integers; the colour divided by alpha again only when the node's Alpha
// output is used; sRGB images linearised after the lookup whatever their depth.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "photon/shading/textures.h"

namespace photon {
namespace textures_alpha_test {
namespace {

namespace fs = std::filesystem;

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

struct TextureAlphaTest : ::testing::Test {
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() / ("photon_texture_alpha_test_" + std::string(info->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    setenv("PHOTON_TEXTURE_CACHE", (dir / "cache").c_str(), 1);
  }
  void TearDown() override { fs::remove_all(dir); }

  // A 2 x 1 RGBA image: texel 0 = (200, 100, 30, 77) / 255, texel 1 opaque white.
  std::string write_png() {
    const unsigned char px[8] = {200, 100, 30, 77, 255, 255, 255, 255};
    const std::string path = (dir / "straight.png").string();
    OIIO::ImageSpec spec(2, 1, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the bytes as they are (no unpremultiply)
    EXPECT_TRUE(OIIO::ImageBuf(spec, const_cast<unsigned char*>(px)).write(path));
    return path;
  }
  // A 2 x 1 float RGB image: 0.2 and 0.8.
  std::string write_exr() {
    const float px[6] = {0.2f, 0.2f, 0.2f, 0.8f, 0.8f, 0.8f};
    const std::string path = (dir / "grey.exr").string();
    OIIO::ImageSpec spec(2, 1, 3, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(OIIO::ImageBuf(spec, const_cast<float*>(px)).write(path));
    return path;
  }
  static ImageTexture texture(const std::string& path, bool srgb, TextureAlpha alpha,
                              bool unassociate, TextureInterpolation interpolation) {
    ImageTexture t;
    t.path = path;
    t.srgb = srgb;
    t.alpha = alpha;
    t.unassociate = unassociate;
    t.interpolation = interpolation;
    t.extension = TextureExtension::kExtend;
    return t;
  }
  fs::path dir;
};

TEST_F(TextureAlphaTest, StraightAlphaIsPremultipliedInIntegersAndUnassociatedOnlyWhenAlphaIsUsed) {
  const std::string png = write_png();
  const auto closest = TextureInterpolation::kClosest;
  std::vector<std::string> warnings;
  const TextureSet set({texture(png, true, TextureAlpha::kAssociate, false, closest),
                        texture(png, true, TextureAlpha::kAssociate, true, closest),
                        texture(png, true, TextureAlpha::kIgnore, false, closest),
                        texture(png, false, TextureAlpha::kKeep, false, closest)},
                       &warnings);
  ASSERT_TRUE(warnings.empty()) << warnings.front();
  const Vec2 texel0{0.25f, 0.5f};
  float rgba[4];
  // Cycles stores c a / 255 truncated: 200 * 77 / 255 = 60, 100 * 77 / 255 = 30, 30 * 77 / 255 = 9.
  const int premul[3] = {60, 30, 9};
  ASSERT_TRUE(set.lookup(0, texel0, rgba));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgba[c], srgb_to_linear(premul[c] / 255.0f), 1e-3f);
  EXPECT_NEAR(rgba[3], 77.0f / 255.0f, 1e-3f);
  // Alpha used: divided by alpha before linearising.
  ASSERT_TRUE(set.lookup(1, texel0, rgba));
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(rgba[c], srgb_to_linear(premul[c] / 77.0f), 2e-3f) << "channel " << c;
  // Alpha mode None: the colour as stored, alpha 1.
  ASSERT_TRUE(set.lookup(2, texel0, rgba));
  EXPECT_NEAR(rgba[0], srgb_to_linear(200.0f / 255.0f), 1e-3f);
  EXPECT_FLOAT_EQ(rgba[3], 1.0f);
  // Non-Color: nothing happens to either.
  ASSERT_TRUE(set.lookup(3, texel0, rgba));
  EXPECT_NEAR(rgba[0], 200.0f / 255.0f, 1e-3f);
  EXPECT_NEAR(rgba[3], 77.0f / 255.0f, 1e-3f);
}

TEST_F(TextureAlphaTest, FloatSrgbImagesAreInterpolatedAsStoredThenLinearised) {
  const std::string exr = write_exr();
  std::vector<std::string> warnings;
  const TextureSet set(
      {texture(exr, true, TextureAlpha::kKeep, false, TextureInterpolation::kLinear)}, &warnings);
  ASSERT_TRUE(warnings.empty()) << warnings.front();
  float rgba[4];
  ASSERT_TRUE(set.lookup(0, Vec2{0.5f, 0.5f}, rgba));  // halfway between the texel centres
  EXPECT_NEAR(rgba[0], srgb_to_linear(0.5f), 1e-3f);   // not (s(0.2) + s(0.8)) / 2 = 0.33
}

}  // namespace
}  // namespace textures_alpha_test
}  // namespace photon

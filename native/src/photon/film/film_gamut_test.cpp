// Spectral mode's pixels outside the Rec.709 gamut: resolved without negative channels, their
// luminance and hue kept, the light passes still summing to the pixel.
#include <gtest/gtest.h>

#include "photon/film/film.h"

namespace photon {
namespace film_gamut_test {
namespace {

Film one_pixel_film(bool into_gamut) {
  FilmOptions options;
  options.light_passes = true;
  options.into_gamut = into_gamut;
  return Film(film_frame(Camera{}, 1, 1, 0, 0, 1, 1), options);
}

struct Resolved {
  Vec3 combined;
  Vec3 passes[kPassCount];
};

Resolved resolve(const Film& film, int samples) {
  Resolved r;
  float rgba[4];
  film.resolve_rgba(FilmRect{0, 0, 1, 1}, samples, rgba);
  r.combined = Vec3(rgba[0], rgba[1], rgba[2]);
  const std::vector<PassImage> passes = film.resolve_passes(FilmRect{0, 0, 1, 1}, samples);
  for (int k = 0; k < kPassCount; ++k)
    r.passes[k] = Vec3(passes[k].pixels[0], passes[k].pixels[1], passes[k].pixels[2]);
  return r;
}

// An 800 K blackbody's Rec.709 colour at luminance 1, split over two passes, summed over 4
// samples.
const Vec3 kDeepRed(5.40694f, -0.201048f, -0.0823191f);

TEST(FilmGamut, DeepRedKeepsItsLuminanceAndHueWithoutNegativeChannels) {
  Film film = one_pixel_film(true);
  const Vec3 passes[kPassCount] = {kDeepRed * 3.0f, kDeepRed * 1.0f, Vec3(0.0f), Vec3(0.0f)};
  film.set_sums(0, kDeepRed * 4.0f, 4.0f, passes);
  const Resolved r = resolve(film, 4);
  EXPECT_GE(r.combined.x, 0.0f);
  EXPECT_FLOAT_EQ(r.combined.y, 0.0f);  // the most negative channel lands on 0
  EXPECT_GE(r.combined.z, 0.0f);
  EXPECT_NEAR(luminance(r.combined), luminance(kDeepRed), 1e-5f);
  EXPECT_GT(r.combined.x, 10.0f * r.combined.z);  // still red
  Vec3 sum(0.0f);
  for (const Vec3& p : r.passes) sum = sum + p;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], r.combined[c], 1e-5f) << c;
  EXPECT_NEAR(r.passes[0].x, 0.75f * r.combined.x, 1e-5f);
}

TEST(FilmGamut, ColoursInsideTheGamutAndRgbModeAreUntouched) {
  for (bool into_gamut : {false, true}) {
    Film film = one_pixel_film(into_gamut);
    const Vec3 inside(0.7f, 0.1f, 0.0f);
    const Vec3 passes[kPassCount] = {inside, Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
    film.set_sums(0, inside, 1.0f, passes);
    const Resolved r = resolve(film, 1);
    EXPECT_EQ(r.combined.x, inside.x);
    EXPECT_EQ(r.combined.y, inside.y);
    EXPECT_EQ(r.combined.z, inside.z);
  }
  Film rgb = one_pixel_film(false);
  rgb.set_sums(0, kDeepRed, 1.0f, nullptr);
  EXPECT_EQ(resolve(rgb, 1).combined.y, kDeepRed.y);  // RGB mode resolves what it summed
}

TEST(FilmGamut, NoiseAboutBlackResolvesToBlack) {
  Film film = one_pixel_film(true);
  const Vec3 dark(0.01f, -0.05f, 0.0f);  // luminance < 0
  const Vec3 passes[kPassCount] = {dark, Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
  film.set_sums(0, dark, 1.0f, passes);
  const Resolved r = resolve(film, 1);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(r.combined[c], 0.0f) << c;
    EXPECT_GE(r.passes[0][c], 0.0f) << c;
  }
}

}  // namespace
}  // namespace film_gamut_test
}  // namespace photon

// RGB -> spectrum uplifting (Jakob & Hanika 2019) with the build-time table: exact grey axis,
// spectra in [0, 1], and the RGB -> spectrum -> XYZ (under D65) -> RGB round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "photon/spectral/illuminants.h"
#include "photon/spectral/rgb_uplift.h"
#include "photon/spectral/uplift_fit.h"

namespace photon::spectral {
namespace uplift_test {
namespace {

const RgbToSpectrumTable& table() {
  return RgbToSpectrumTable::rec709();
}

template <class S>
TabulatedSpectrum tabulate(const S& s) {
  return TabulatedSpectrum::from_function([&](float lambda) { return s(lambda); });
}

// Colour of a reflectance spectrum under D65, back in linear Rec.709.
template <class S>
Vec3 reflectance_rgb(const S& s) {
  return xyz_to_rec709(reflectance_to_xyz(tabulate(s), illuminant_spectrum(Illuminant::kD65)));
}

float round_trip_error(const Vec3& rgb) {
  return max_abs_component(reflectance_rgb(RgbAlbedoSpectrum(table(), rgb)) - rgb);
}

TEST(SpectralUplift, GreyAxisIsExact) {
  const RgbAlbedoSpectrum one(table(), Vec3(1.0f));
  const RgbAlbedoSpectrum zero(table(), Vec3(0.0f));
  for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 0.5f) {
    EXPECT_EQ(one(lambda), 1.0f) << lambda;
    EXPECT_EQ(zero(lambda), 0.0f) << lambda;
  }
  for (float v : {0.001f, 0.18f, 0.5f, 0.73f, 0.999f}) {
    const RgbAlbedoSpectrum grey(table(), Vec3(v));
    for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 7.0f)
      EXPECT_NEAR(grey(lambda), v, 1e-6f) << v << " at " << lambda;
  }
  // Out of range grey clamps to the ends.
  EXPECT_EQ(RgbAlbedoSpectrum(table(), Vec3(3.0f))(500.0f), 1.0f);
  EXPECT_EQ(RgbAlbedoSpectrum(table(), Vec3(-1.0f))(500.0f), 0.0f);
}

TEST(SpectralUplift, ReflectancesStayInUnitInterval) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.2f, 1.2f);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 rgb(u(rng), u(rng), u(rng));
    const RgbAlbedoSpectrum s(table(), rgb);
    for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 3.0f) {
      const float v = s(lambda);
      ASSERT_GE(v, 0.0f) << rgb.x << " " << rgb.y << " " << rgb.z << " at " << lambda;
      ASSERT_LE(v, 1.0f) << rgb.x << " " << rgb.y << " " << rgb.z << " at " << lambda;
    }
  }
}

TEST(SpectralUplift, RoundTripOnGridAndRandomColours) {
  // The grey axis is exact in the spectrum; its colour error is D65's own: the tabulated
  // illuminant's white (x, y = 0.31272, 0.32903) against Rec.709's nominal (0.3127, 0.3290),
  // 2.4e-4 at (1,1,1). worst_chromatic is the table's error on every other colour.
  float worst = 0.0f, worst_chromatic = 0.0f;
  Vec3 worst_rgb;
  auto record = [&](const Vec3& rgb) {
    const float e = round_trip_error(rgb);
    if (e > worst) worst = e, worst_rgb = rgb;
    if (!(rgb.x == rgb.y && rgb.y == rgb.z)) worst_chromatic = std::max(worst_chromatic, e);
  };
  const int n = 16;
  for (int r = 0; r <= n; ++r)
    for (int g = 0; g <= n; ++g)
      for (int b = 0; b <= n; ++b) {
        record(Vec3(r / float(n), g / float(n), b / float(n)));
      }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    // Every third colour dark (max < 0.1, below the darkest fitted node) or near white.
    Vec3 rgb(u(rng), u(rng), u(rng));
    if (i % 3 == 1) rgb = rgb * 0.1f;
    if (i % 3 == 2) rgb = Vec3(1.0f) - rgb * 0.05f;
    record(rgb);
  }
  std::printf(
      "uplift round trip (table %d^3): max error %.3g at (%g, %g, %g), %.3g off the "
      "grey axis\n",
      table().resolution(), worst, worst_rgb.x, worst_rgb.y, worst_rgb.z, worst_chromatic);
  EXPECT_LT(worst, 1e-3f);
  EXPECT_LT(worst_chromatic, 1e-3f);
}

TEST(SpectralUplift, SampledMatchesContinuous) {
  const RgbAlbedoSpectrum s(table(), Vec3(0.8f, 0.3f, 0.1f));
  const auto wl = SampledWavelengths::sample_uniform(0.42f);
  const SampledSpectrum v = s.sample(wl);
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_EQ(v[i], s(wl.lambda(i)));
}

TEST(SpectralUplift, UnboundedScalesBack) {
  for (const Vec3& rgb :
       {Vec3(3.0f, 1.5f, 0.2f), Vec3(0.2f, 0.1f, 0.05f), Vec3(10.0f), Vec3(0.0f, 7.0f, 0.0f)}) {
    const RgbUnboundedSpectrum s(table(), rgb);
    const Vec3 back = reflectance_rgb(s);
    EXPECT_LT(max_abs_component(back - rgb), 1e-3f * std::max(1.0f, max_component(rgb)))
        << rgb.x << " " << rgb.y << " " << rgb.z;
  }
  EXPECT_EQ(RgbUnboundedSpectrum(table(), Vec3(0.0f))(550.0f), 0.0f);
}

TEST(SpectralUplift, IlluminantWhiteIsD65AndColoursRoundTrip) {
  const RgbIlluminantSpectrum white(table(), Vec3(1.0f));
  const auto& d65 = illuminant_spectrum(Illuminant::kD65);
  for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 10.0f)
    EXPECT_FLOAT_EQ(white(lambda), d65(lambda));
  const Vec3 w = xyz_to_rec709(emission_to_xyz(tabulate(white)));
  EXPECT_NEAR(w.x, 1.0f, 1e-3f);
  EXPECT_NEAR(w.y, 1.0f, 1e-3f);
  EXPECT_NEAR(w.z, 1.0f, 1e-3f);
  for (const Vec3& rgb : {Vec3(2.0f, 0.5f, 0.1f), Vec3(0.1f, 0.2f, 5.0f), Vec3(0.3f)}) {
    const RgbIlluminantSpectrum s(table(), rgb);
    const Vec3 back = xyz_to_rec709(emission_to_xyz(tabulate(s)));
    EXPECT_LT(max_abs_component(back - rgb), 1e-3f * std::max(1.0f, max_component(rgb)));
  }
}

TEST(SpectralUplift, BadInputGivesFiniteSpectra) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const Vec3& rgb : {Vec3(nan, 0.5f, 0.2f), Vec3(inf, 0.0f, 1.0f), Vec3(-inf, nan, -2.0f)}) {
    const RgbAlbedoSpectrum a(table(), rgb);
    const RgbUnboundedSpectrum u(table(), rgb);
    const RgbIlluminantSpectrum l(table(), rgb);
    for (float lambda : {360.0f, 550.0f, 830.0f, nan}) {
      EXPECT_TRUE(std::isfinite(a(lambda)));
      EXPECT_TRUE(std::isfinite(u(lambda)));
      EXPECT_TRUE(std::isfinite(l(lambda)));
    }
  }
}

TEST(SpectralUplift, OptimiserReachesSaturatedPrimaries) {
  // The fit itself (what the table generator runs): the sRGB primaries and secondaries at full
  // strength are reflectances under D65 and must be reached to well below 1e-4.
  const UpliftFitter fitter;
  for (const Vec3& rgb : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0), Vec3(0, 1, 1),
                          Vec3(1, 0, 1), Vec3(0.5f, 0.2f, 0.1f)}) {
    double c[3] = {0.0, 0.0, 0.0};
    fitter.fit(rgb, c);
    double out[3];
    fitter.rgb_of(c, out);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(out[k], rgb[k], 1e-5) << k;
  }
}

TEST(SpectralUplift, TableFitDoesNotDependOnThreadCount) {
  const UpliftTableData one = build_uplift_table(6, 1);
  const UpliftTableData three = build_uplift_table(6, 3);
  ASSERT_EQ(one.coeffs.size(), three.coeffs.size());
  EXPECT_EQ(one.coeffs, three.coeffs);
  EXPECT_EQ(one.z_nodes, three.z_nodes);
  EXPECT_EQ(one.z_nodes.front(), 0.0f);
  EXPECT_EQ(one.z_nodes.back(), 1.0f);
}

}  // namespace
}  // namespace uplift_test
}  // namespace photon::spectral

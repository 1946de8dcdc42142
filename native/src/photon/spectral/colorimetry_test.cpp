// CIE tables, illuminants and the XYZ / Rec.709 / Lab maps against published CIE values.
#include "photon/spectral/colorimetry.h"

#include <gtest/gtest.h>

#include "photon/spectral/cie.h"
#include "photon/spectral/illuminants.h"

namespace photon::spectral {
namespace colorimetry_test {
namespace {

Vec3 chromaticity(const Vec3& xyz) {
  const float s = xyz.x + xyz.y + xyz.z;
  return {xyz.x / s, xyz.y / s, 0.0f};
}

TEST(SpectralCie, TableValuesAndIntegral) {
  EXPECT_FLOAT_EQ(cie_xyz(555.0f).y, 1.0f);
  EXPECT_FLOAT_EQ(cie_xyz(600.0f).x, 1.0622f);
  EXPECT_FLOAT_EQ(cie_xyz(445.0f).z, 1.7826f);
  EXPECT_EQ(cie_xyz(650.0f).z, 0.0f);
  EXPECT_GT(cie_xyz(649.0f).z, 0.0f);
  EXPECT_NEAR(cie_xyz(555.5f).y, 0.5f * (1.0f + 0.9998567f), 1e-6f);
  EXPECT_EQ(cie_xyz(359.0f).x, 0.0f);
  EXPECT_EQ(cie_xyz(831.0f).y, 0.0f);
  // The integral of y over 360..830 nm at 1 nm (CIE 15:2004; pbrt-v4's CIE_Y_integral).
  EXPECT_NEAR(cie_y_integral(), 106.856895f, 1e-3f);
}

TEST(SpectralCie, EqualEnergyWhiteIsAtOneThird) {
  // The CIE 1931 functions are normalised to equal areas: illuminant E sits at (1/3, 1/3)
  // (on the 1 nm table the sums of x and z differ from y's by 1e-4 and 3.3e-4).
  const auto e = TabulatedSpectrum::from_function([](float) { return 1.0f; });
  const Vec3 xyz = emission_to_xyz(e);
  EXPECT_NEAR(xyz.y, 1.0f, 1e-6f);
  EXPECT_NEAR(xyz.x, 1.0f, 5e-4f);
  EXPECT_NEAR(xyz.z, 1.0f, 5e-4f);
}

TEST(SpectralCie, Rec709MatrixMatchesSrgbStandard) {
  // IEC 61966-2-1 (sRGB) RGB -> XYZ, 4 decimals.
  const double ref[3][3] = {
      {0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rec709_to_xyz_matrix().m[r][c], ref[r][c], 1e-4);
  const Vec3 back = xyz_to_rec709(rec709_to_xyz(Vec3(0.2f, 0.5f, 0.9f)));
  EXPECT_NEAR(back.x, 0.2f, 1e-6f);
  EXPECT_NEAR(back.y, 0.5f, 1e-6f);
  EXPECT_NEAR(back.z, 0.9f, 1e-6f);
}

// Chromaticities of the CIE illuminants for the 2-degree observer (CIE 15:2004, Table T.3 and
// T.8.1).
struct IlluminantCase {
  Illuminant which;
  float x, y, tolerance;
};

TEST(SpectralCie, IlluminantChromaticities) {
  const IlluminantCase cases[] = {{Illuminant::kD65, 0.31272f, 0.32903f, 1e-4f},
                                  {Illuminant::kA, 0.44757f, 0.40745f, 2e-4f},
                                  {Illuminant::kF2, 0.37208f, 0.37529f, 1e-3f},
                                  {Illuminant::kF7, 0.31292f, 0.32933f, 1e-3f},
                                  {Illuminant::kF11, 0.38052f, 0.37713f, 1e-3f}};
  for (const auto& c : cases) {
    const Vec3 xyz = emission_to_xyz(illuminant_spectrum(c.which));
    EXPECT_NEAR(xyz.y, 1.0f, 1e-5f) << static_cast<int>(c.which);
    const Vec3 xy = chromaticity(xyz);
    EXPECT_NEAR(xy.x, c.x, c.tolerance) << static_cast<int>(c.which);
    EXPECT_NEAR(xy.y, c.y, c.tolerance) << static_cast<int>(c.which);
  }
}

TEST(SpectralCie, D65IsRec709White) {
  const Vec3 rgb = xyz_to_rec709(emission_to_xyz(illuminant_spectrum(Illuminant::kD65)));
  EXPECT_NEAR(rgb.x, 1.0f, 1e-3f);
  EXPECT_NEAR(rgb.y, 1.0f, 1e-3f);
  EXPECT_NEAR(rgb.z, 1.0f, 1e-3f);
  // A perfect reflector under D65 has exactly the illuminant's colour.
  const auto one = TabulatedSpectrum::from_function([](float) { return 1.0f; });
  const Vec3 refl = reflectance_to_xyz(one, illuminant_spectrum(Illuminant::kD65));
  EXPECT_NEAR(refl.y, 1.0f, 1e-6f);
}

TEST(SpectralCie, LabOfWhiteAndGrey) {
  const Vec3 white(0.9505f, 1.0f, 1.089f);
  const Vec3 lab = xyz_to_lab(white, white);
  EXPECT_NEAR(lab.x, 100.0f, 1e-4f);
  EXPECT_NEAR(lab.y, 0.0f, 1e-4f);
  EXPECT_NEAR(lab.z, 0.0f, 1e-4f);
  // Y = 0.18 is L* = 116 * 0.18^(1/3) - 16 = 49.5.
  EXPECT_NEAR(xyz_to_lab(white * 0.18f, white).x, 49.496f, 1e-2f);
  // The linear segment near black: L* = 903.3 Y.
  EXPECT_NEAR(xyz_to_lab(white * 0.001f, white).x, 0.9033f, 1e-3f);
}

TEST(SpectralCie, TabulatedSpectrumInterpolatesAndClips) {
  const float v[3] = {1.0f, 3.0f, 5.0f};
  const auto s = TabulatedSpectrum::from_samples(400.0f, 10.0f, v, 3);
  EXPECT_EQ(s(399.0f), 0.0f);
  EXPECT_FLOAT_EQ(s(400.0f), 1.0f);
  EXPECT_FLOAT_EQ(s(405.0f), 2.0f);
  EXPECT_FLOAT_EQ(s(415.5f), 4.1f);
  EXPECT_FLOAT_EQ(s(420.0f), 5.0f);
  EXPECT_EQ(s(421.0f), 0.0f);
  EXPECT_EQ(s(std::nanf("")), 0.0f);
}

}  // namespace
}  // namespace colorimetry_test
}  // namespace photon::spectral

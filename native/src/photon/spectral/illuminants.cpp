// Data: CIE 15:2004 "Colorimetry" (3rd ed.), Table T.2 (daylight components S0, S1, S2 at
// 10 nm, 300..830 nm) and Table T.6 (fluorescent illuminants F2, F7, F11 at 5 nm, 380..780 nm,
// as reprinted in ASTM E308).
#include "photon/spectral/illuminants.h"

#include <cmath>

namespace photon::spectral {
namespace {

constexpr float kDaylightS0[] = {
    0.04f,  6.0f,   29.6f,  55.3f,  57.3f,  61.8f,  61.5f,  68.8f,  63.4f,  65.8f,  94.8f,
    104.8f, 105.9f, 96.8f,  113.9f, 125.6f, 125.5f, 121.3f, 121.3f, 113.5f, 113.1f, 110.8f,
    106.5f, 108.8f, 105.3f, 104.4f, 100.0f, 96.0f,  95.1f,  89.1f,  90.5f,  90.3f,  88.4f,
    84.0f,  85.1f,  81.9f,  82.6f,  84.9f,  81.3f,  71.9f,  74.3f,  76.4f,  63.3f,  71.7f,
    77.0f,  65.2f,  47.7f,  68.6f,  65.0f,  66.0f,  61.0f,  53.3f,  58.9f,  61.9f};
constexpr float kDaylightS1[] = {
    0.02f,  4.5f,   22.4f,  42.0f,  40.6f,  41.6f,  38.0f,  42.4f,  38.5f,  35.0f,  43.4f,
    46.3f,  43.9f,  37.1f,  36.7f,  35.9f,  32.6f,  27.9f,  24.3f,  20.1f,  16.2f,  13.2f,
    8.6f,   6.1f,   4.2f,   1.9f,   0.0f,   -1.6f,  -3.5f,  -3.5f,  -5.8f,  -7.2f,  -8.6f,
    -9.5f,  -10.9f, -10.7f, -12.0f, -14.0f, -13.6f, -12.0f, -13.3f, -12.9f, -10.6f, -11.6f,
    -12.2f, -10.2f, -7.8f,  -11.2f, -10.4f, -10.6f, -9.7f,  -8.3f,  -9.3f,  -9.8f};
constexpr float kDaylightS2[] = {0.0f,  2.0f,  4.0f,  8.5f,  7.8f,  6.7f,  5.3f,  6.1f,  3.0f,
                                 1.2f,  -1.1f, -0.5f, -0.7f, -1.2f, -2.6f, -2.9f, -2.8f, -2.6f,
                                 -2.6f, -1.8f, -1.5f, -1.3f, -1.2f, -1.0f, -0.5f, -0.3f, 0.0f,
                                 0.2f,  0.5f,  2.1f,  3.2f,  4.1f,  4.7f,  5.1f,  6.7f,  7.3f,
                                 8.6f,  9.8f,  10.2f, 8.3f,  9.6f,  8.5f,  7.0f,  7.6f,  8.0f,
                                 6.7f,  5.2f,  7.4f,  6.8f,  7.0f,  6.4f,  5.5f,  6.1f,  6.5f};
constexpr int kDaylightCount = sizeof(kDaylightS0) / sizeof(float);
static_assert(kDaylightCount == 54, "300..830 nm every 10 nm");

constexpr float kF2[] = {
    1.18f,  1.48f,  1.84f,  2.15f,  3.44f,  15.69f, 3.85f,  3.74f,  4.19f,  4.62f,  5.06f,  34.98f,
    11.81f, 6.27f,  6.63f,  6.93f,  7.19f,  7.4f,   7.54f,  7.62f,  7.65f,  7.62f,  7.62f,  7.45f,
    7.28f,  7.15f,  7.05f,  7.04f,  7.16f,  7.47f,  8.04f,  8.88f,  10.01f, 24.88f, 16.64f, 14.59f,
    16.16f, 17.56f, 18.62f, 21.47f, 22.79f, 19.29f, 18.66f, 17.73f, 16.54f, 15.21f, 13.8f,  12.36f,
    10.95f, 9.65f,  8.4f,   7.32f,  6.31f,  5.43f,  4.68f,  4.02f,  3.45f,  2.96f,  2.55f,  2.19f,
    1.89f,  1.64f,  1.53f,  1.27f,  1.1f,   0.99f,  0.88f,  0.76f,  0.68f,  0.61f,  0.56f,  0.54f,
    0.51f,  0.47f,  0.47f,  0.43f,  0.46f,  0.47f,  0.4f,   0.33f,  0.27f};
constexpr float kF7[] = {
    2.56f,  3.18f,  3.84f,  4.53f,  6.15f,  19.37f, 7.37f,  7.05f,  7.71f,  8.41f,  9.15f,  44.14f,
    17.52f, 11.35f, 12.0f,  12.58f, 13.08f, 13.45f, 13.71f, 13.88f, 13.95f, 13.93f, 13.82f, 13.64f,
    13.43f, 13.25f, 13.08f, 12.93f, 12.78f, 12.6f,  12.44f, 12.33f, 12.26f, 29.52f, 17.05f, 12.44f,
    12.58f, 12.72f, 12.83f, 15.46f, 16.75f, 12.83f, 12.67f, 12.45f, 12.19f, 11.89f, 11.6f,  11.35f,
    11.12f, 10.95f, 10.76f, 10.42f, 10.11f, 10.04f, 10.02f, 10.11f, 9.87f,  8.65f,  7.27f,  6.44f,
    5.83f,  5.41f,  5.04f,  4.57f,  4.12f,  3.77f,  3.46f,  3.08f,  2.73f,  2.47f,  2.25f,  2.06f,
    1.9f,   1.75f,  1.62f,  1.54f,  1.45f,  1.32f,  1.17f,  0.99f,  0.81f};
constexpr float kF11[] = {
    0.91f,  0.63f,  0.46f,  0.37f, 1.29f,  12.68f, 1.59f,  1.79f, 2.46f,  3.38f,  4.49f,  33.94f,
    12.13f, 6.95f,  7.19f,  7.12f, 6.72f,  6.13f,  5.46f,  4.79f, 5.66f,  14.29f, 14.96f, 8.97f,
    4.72f,  2.33f,  1.47f,  1.1f,  0.89f,  0.83f,  1.18f,  4.9f,  39.59f, 72.84f, 32.61f, 7.52f,
    2.83f,  1.96f,  1.67f,  4.43f, 11.28f, 14.76f, 12.73f, 9.74f, 7.33f,  9.72f,  55.27f, 42.58f,
    13.18f, 13.16f, 12.26f, 5.11f, 2.07f,  2.34f,  3.58f,  3.01f, 2.48f,  2.14f,  1.54f,  1.33f,
    1.46f,  1.94f,  2.0f,   1.2f,  1.35f,  4.1f,   5.58f,  2.51f, 0.57f,  0.27f,  0.23f,  0.21f,
    0.24f,  0.24f,  0.2f,   0.24f, 0.32f,  0.26f,  0.16f,  0.12f, 0.09f};
static_assert(sizeof(kF2) == 81 * sizeof(float) && sizeof(kF7) == 81 * sizeof(float) &&
                  sizeof(kF11) == 81 * sizeof(float),
              "380..780 nm every 5 nm");

// D65 by the procedure of CIE 15:2004, Section 3.1 and note 5 to Table T.1: nominal CCT
// 6500 K * 1.4388 / 1.4380, daylight chromaticity x_D, y_D, the weights M1, M2 of S1, S2
// rounded to three decimals, S = S0 + M1 S1 + M2 S2 every 10 nm, linear in between.
TabulatedSpectrum daylight_d65() {
  const double t = 6500.0 * 1.4388 / 1.4380;
  const double xd = -4.6070e9 / (t * t * t) + 2.9678e6 / (t * t) + 0.09911e3 / t + 0.244063;
  const double yd = -3.000 * xd * xd + 2.870 * xd - 0.275;
  const double m = 0.0241 + 0.2562 * xd - 0.7341 * yd;
  const double m1 = std::round((-1.3515 - 1.7703 * xd + 5.9114 * yd) / m * 1000.0) / 1000.0;
  const double m2 = std::round((0.0300 - 31.4424 * xd + 30.0717 * yd) / m * 1000.0) / 1000.0;
  float s[kDaylightCount];
  for (int i = 0; i < kDaylightCount; ++i)
    s[i] = static_cast<float>(kDaylightS0[i] + m1 * kDaylightS1[i] + m2 * kDaylightS2[i]);
  return TabulatedSpectrum::from_samples(300.0f, 10.0f, s, kDaylightCount);
}

TabulatedSpectrum normalized(TabulatedSpectrum s) {
  const float y = emission_to_xyz(s).y;
  if (y > 0.0f) s.scale(1.0f / y);
  return s;
}

// Physical constants (CODATA 2018, exact in the SI).
constexpr double kPlanck = 6.62607015e-34;
constexpr double kLight = 299792458.0;
constexpr double kBoltzmann = 1.380649e-23;
constexpr double kWien = 2.897771955e-3;

double planck(double lambda_m, double kelvin) {
  const double l5 = lambda_m * lambda_m * lambda_m * lambda_m * lambda_m;
  return 2.0 * kPlanck * kLight * kLight /
         (l5 * std::expm1(kPlanck * kLight / (lambda_m * kBoltzmann * kelvin)));
}

}  // namespace

float blackbody(float lambda, float kelvin) {
  if (!(kelvin > 0.0f) || !std::isfinite(kelvin) || !(lambda > 0.0f)) return 0.0f;
  return static_cast<float>(planck(lambda * 1e-9, kelvin));
}

float blackbody_normalized(float lambda, float kelvin) {
  if (!(kelvin > 0.0f) || !std::isfinite(kelvin) || !(lambda > 0.0f)) return 0.0f;
  return static_cast<float>(planck(lambda * 1e-9, kelvin) / planck(kWien / kelvin, kelvin));
}

Vec3 blackbody_rec709_chroma(float kelvin) {
  if (!(kelvin > 0.0f) || !std::isfinite(kelvin)) return Vec3(0.0f);
  const auto s = TabulatedSpectrum::from_function(
      [kelvin](float lambda) { return blackbody_normalized(lambda, kelvin); });
  const Vec3 xyz = emission_to_xyz(s);
  if (!(xyz.y > 0.0f)) return Vec3(0.0f);
  return xyz_to_rec709(xyz / xyz.y);
}

const TabulatedSpectrum& illuminant_spectrum(Illuminant which) {
  static const TabulatedSpectrum d65 = normalized(daylight_d65());
  static const TabulatedSpectrum a = normalized(TabulatedSpectrum::from_function(
      [](float lambda) { return blackbody_normalized(lambda, 2856.0f); }));
  static const TabulatedSpectrum f2 = normalized(TabulatedSpectrum::from_samples(380, 5, kF2, 81));
  static const TabulatedSpectrum f7 = normalized(TabulatedSpectrum::from_samples(380, 5, kF7, 81));
  static const TabulatedSpectrum f11 =
      normalized(TabulatedSpectrum::from_samples(380, 5, kF11, 81));
  switch (which) {
    case Illuminant::kA:
      return a;
    case Illuminant::kF2:
      return f2;
    case Illuminant::kF7:
      return f7;
    case Illuminant::kF11:
      return f11;
    case Illuminant::kD65:
    default:
      return d65;
  }
}

}  // namespace photon::spectral

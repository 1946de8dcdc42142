#include "photon/spectral/colorimetry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace photon::spectral {
namespace {

Mat3 invert(const Mat3& a) {
  const auto& m = a.m;
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Mat3 r;
  r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

// RGB -> XYZ from the primaries' and the white's chromaticities (SMPTE RP 177): the columns
// are the primaries' XYZ, scaled so that RGB (1,1,1) maps to the white with Y = 1.
Mat3 rgb_to_xyz_from_chromaticities() {
  const double prim[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  const double wx = 0.3127, wy = 0.3290;
  Mat3 p;
  for (int c = 0; c < 3; ++c) {
    const double x = prim[c][0], y = prim[c][1];
    p.m[0][c] = x / y;
    p.m[1][c] = 1.0;
    p.m[2][c] = (1.0 - x - y) / y;
  }
  const Mat3 inv = invert(p);
  const double w[3] = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
  Mat3 r;
  for (int c = 0; c < 3; ++c) {
    const double s = inv.m[c][0] * w[0] + inv.m[c][1] * w[1] + inv.m[c][2] * w[2];
    for (int row = 0; row < 3; ++row) r.m[row][c] = p.m[row][c] * s;
  }
  return r;
}

}  // namespace

TabulatedSpectrum TabulatedSpectrum::from_samples(float lambda0, float step, const float* values,
                                                  int count) {
  TabulatedSpectrum s;
  if (count <= 0 || !(step > 0.0f)) return s;
  for (int i = 0; i < kTableSamples; ++i) {
    const float t = (kLambdaMin + static_cast<float>(i) - lambda0) / step;
    if (t < 0.0f || t > static_cast<float>(count - 1)) continue;
    const int k = std::min(static_cast<int>(t), count - 2 < 0 ? 0 : count - 2);
    const float f = t - static_cast<float>(k);
    s.values_[i] = count == 1 ? values[0] : values[k] + f * (values[k + 1] - values[k]);
  }
  return s;
}

float TabulatedSpectrum::operator()(float lambda) const {
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0.0f;  // NaN too
  const float t = lambda - kLambdaMin;
  const int i = std::min(static_cast<int>(t), kTableSamples - 2);
  const float f = t - static_cast<float>(i);
  return values_[i] + f * (values_[i + 1] - values_[i]);
}

Vec3 emission_to_xyz(const TabulatedSpectrum& s) {
  const float* x = cie_x_table();
  const float* y = cie_y_table();
  const float* z = cie_z_table();
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < kTableSamples; ++i) {
    X += static_cast<double>(s.at(i)) * x[i];
    Y += static_cast<double>(s.at(i)) * y[i];
    Z += static_cast<double>(s.at(i)) * z[i];
  }
  const double n = cie_y_integral();
  return {static_cast<float>(X / n), static_cast<float>(Y / n), static_cast<float>(Z / n)};
}

Vec3 reflectance_to_xyz(const TabulatedSpectrum& r, const TabulatedSpectrum& illuminant) {
  const float* x = cie_x_table();
  const float* y = cie_y_table();
  const float* z = cie_z_table();
  double X = 0, Y = 0, Z = 0, n = 0;
  for (int i = 0; i < kTableSamples; ++i) {
    const double ri = static_cast<double>(r.at(i)) * illuminant.at(i);
    X += ri * x[i];
    Y += ri * y[i];
    Z += ri * z[i];
    n += static_cast<double>(illuminant.at(i)) * y[i];
  }
  if (!(n > 0.0)) return Vec3(0.0f);
  return {static_cast<float>(X / n), static_cast<float>(Y / n), static_cast<float>(Z / n)};
}

Vec3 sampled_to_xyz(const SampledSpectrum& radiance, const SampledWavelengths& wl) {
  Vec3 sum(0.0f);
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const float pdf = wl.pdf(i);
    if (pdf == 0.0f) continue;
    sum += cie_xyz(wl.lambda(i)) * (radiance[i] / pdf);
  }
  return sum / (static_cast<float>(kSpectrumSamples) * cie_y_integral());
}

const Mat3& rec709_to_xyz_matrix() {
  static const Mat3 m = rgb_to_xyz_from_chromaticities();
  return m;
}

const Mat3& xyz_to_rec709_matrix() {
  static const Mat3 m = invert(rec709_to_xyz_matrix());
  return m;
}

Vec3 wavelength_rec709(float lambda) {
  // Tabulated every 1 nm (xyz_to_rec709 of cie_xyz / integral), linearly interpolated.
  static const std::array<Vec3, kTableSamples> table = [] {
    std::array<Vec3, kTableSamples> t;
    const float inv = 1.0f / cie_y_integral();
    for (int i = 0; i < kTableSamples; ++i) t[i] = xyz_to_rec709(cie_xyz(kLambdaMin + i) * inv);
    return t;
  }();
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return Vec3(0.0f);
  const float x = lambda - kLambdaMin;
  const int i = std::min(static_cast<int>(x), kTableSamples - 2);
  const float f = x - static_cast<float>(i);
  return table[i] + (table[i + 1] - table[i]) * f;
}

Vec3 xyz_to_lab(const Vec3& xyz, const Vec3& white) {
  // f(t) = t^(1/3) above (6/29)^3, linear below (CIE 15:2004, Section 8.2.1).
  auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  };
  const double fx = f(xyz.x / white.x), fy = f(xyz.y / white.y), fz = f(xyz.z / white.z);
  return {static_cast<float>(116.0 * fy - 16.0), static_cast<float>(500.0 * (fx - fy)),
          static_cast<float>(200.0 * (fy - fz))};
}

}  // namespace photon::spectral

#include "photon/spectral/uplift_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

#include "photon/spectral/cie.h"
#include "photon/spectral/colorimetry.h"
#include "photon/spectral/illuminants.h"

namespace photon::spectral {
namespace {

constexpr int kMaxIterations = 64;
// Delta E*ab at which a fit is done: far below what is visible, and about 1e-7 in RGB.
constexpr double kTolerance = 1e-6;
// The paper's safeguard: coefficients whose largest magnitude passes this are scaled back,
// which keeps S's argument finite for saturated colours (the spectrum is then a near-step).
// The paper's 200 leaves colours next to white, e.g. (1, 0.97, 0.97), 1e-3 off; at 1000 the
// float evaluation of the quadratic is still within 1e-4 of the double one.
constexpr double kMaxCoefficient = 1000.0;

bool solve3(const double a[3][3], const double b[3], double x[3]) {
  // Cramer's rule: the systems are 3x3 and well scaled.
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (!(std::fabs(det) > 1e-300)) return false;
  for (int k = 0; k < 3; ++k) {
    double m[3][3];
    std::memcpy(m, a, sizeof(m));
    for (int r = 0; r < 3; ++r) m[r][k] = b[r];
    const double dk = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                      m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                      m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    x[k] = dk / det;
  }
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

double norm3(const double v[3]) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

double smoothstep(double x) {
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

UpliftFitter::UpliftFitter() {
  const TabulatedSpectrum& d65 = illuminant_spectrum(Illuminant::kD65);
  const float* cmf[3] = {cie_x_table(), cie_y_table(), cie_z_table()};
  double norm = 0.0;
  for (int i = 0; i < kTableSamples; ++i) norm += static_cast<double>(d65.at(i)) * cmf[1][i];
  t_.resize(kTableSamples);
  for (int c = 0; c < 3; ++c) {
    w_[c].resize(kTableSamples);
    white_[c] = 0.0;
  }
  for (int i = 0; i < kTableSamples; ++i) {
    t_[i] = static_cast<double>(i) / (kTableSamples - 1);
    for (int c = 0; c < 3; ++c) {
      w_[c][i] = static_cast<double>(d65.at(i)) * cmf[c][i] / norm;
      white_[c] += w_[c][i];
    }
  }
  std::memcpy(xyz_to_rgb_, xyz_to_rec709_matrix().m, sizeof(xyz_to_rgb_));
  std::memcpy(rgb_to_xyz_, rec709_to_xyz_matrix().m, sizeof(rgb_to_xyz_));
}

void UpliftFitter::xyz_and_jacobian(const double c[3], double xyz[3], double jac[3][3]) const {
  for (int r = 0; r < 3; ++r) {
    xyz[r] = 0.0;
    for (int k = 0; k < 3; ++k) jac[r][k] = 0.0;
  }
  for (int i = 0; i < kTableSamples; ++i) {
    const double t = t_[i];
    const double x = (c[0] * t + c[1]) * t + c[2];
    const double q = 1.0 / std::sqrt(1.0 + x * x);
    const double s = 0.5 + 0.5 * x * q;  // S(x)
    const double ds = 0.5 * q * q * q;   // S'(x) = 1 / (2 (1 + x^2)^(3/2))
    const double g[3] = {ds * t * t, ds * t, ds};
    for (int r = 0; r < 3; ++r) {
      const double w = w_[r][i];
      xyz[r] += w * s;
      for (int k = 0; k < 3; ++k) jac[r][k] += w * g[k];
    }
  }
}

void UpliftFitter::lab_of(const double xyz[3], double lab[3], double dlab[3][3]) const {
  constexpr double d = 6.0 / 29.0;
  double f[3], df[3];
  for (int c = 0; c < 3; ++c) {
    const double v = xyz[c] / white_[c];
    if (v > d * d * d) {
      f[c] = std::cbrt(v);
      df[c] = 1.0 / (3.0 * f[c] * f[c] * white_[c]);
    } else {
      f[c] = v / (3.0 * d * d) + 4.0 / 29.0;
      df[c] = 1.0 / (3.0 * d * d * white_[c]);
    }
  }
  lab[0] = 116.0 * f[1] - 16.0;
  lab[1] = 500.0 * (f[0] - f[1]);
  lab[2] = 200.0 * (f[1] - f[2]);
  const double j[3][3] = {{0.0, 116.0 * df[1], 0.0},
                          {500.0 * df[0], -500.0 * df[1], 0.0},
                          {0.0, 200.0 * df[1], -200.0 * df[2]}};
  std::memcpy(dlab, j, sizeof(j));
}

void UpliftFitter::rgb_of(const double coeffs[3], double rgb[3]) const {
  double xyz[3], jac[3][3];
  xyz_and_jacobian(coeffs, xyz, jac);
  for (int r = 0; r < 3; ++r)
    rgb[r] = xyz_to_rgb_[r][0] * xyz[0] + xyz_to_rgb_[r][1] * xyz[1] + xyz_to_rgb_[r][2] * xyz[2];
}

double UpliftFitter::fit(const Vec3& rgb, double coeffs[3]) const {
  double target_xyz[3], target[3], unused[3][3];
  for (int r = 0; r < 3; ++r)
    target_xyz[r] =
        rgb_to_xyz_[r][0] * rgb.x + rgb_to_xyz_[r][1] * rgb.y + rgb_to_xyz_[r][2] * rgb.z;
  lab_of(target_xyz, target, unused);

  // Residual and Jacobian (in Lab) at c.
  auto evaluate = [&](const double c[3], double res[3], double jac[3][3]) {
    double xyz[3], dxyz[3][3], lab[3], dlab[3][3];
    xyz_and_jacobian(c, xyz, dxyz);
    lab_of(xyz, lab, dlab);
    for (int r = 0; r < 3; ++r) {
      res[r] = target[r] - lab[r];
      for (int k = 0; k < 3; ++k)
        jac[r][k] = dlab[r][0] * dxyz[0][k] + dlab[r][1] * dxyz[1][k] + dlab[r][2] * dxyz[2][k];
    }
    return norm3(res);
  };

  double res[3], jac[3][3];
  double err = evaluate(coeffs, res, jac);
  for (int it = 0; it < kMaxIterations && err > kTolerance; ++it) {
    double step[3];
    if (!solve3(jac, res, step)) break;
    // Gauss-Newton step, halved while it does not reduce the residual (a damped line search:
    // saturated targets make the full step overshoot).
    bool improved = false;
    for (int h = 0; h < 24 && !improved; ++h) {
      double trial[3] = {coeffs[0] + step[0], coeffs[1] + step[1], coeffs[2] + step[2]};
      const double m = std::max({std::fabs(trial[0]), std::fabs(trial[1]), std::fabs(trial[2])});
      if (m > kMaxCoefficient)
        for (double& v : trial) v *= kMaxCoefficient / m;
      double tres[3], tjac[3][3];
      const double terr = evaluate(trial, tres, tjac);
      if (terr < err) {
        std::memcpy(coeffs, trial, sizeof(trial));
        std::memcpy(res, tres, sizeof(tres));
        std::memcpy(jac, tjac, sizeof(tjac));
        err = terr;
        improved = true;
      } else {
        for (double& v : step) v *= 0.5;
      }
    }
    if (!improved) break;
  }
  return err;
}

float uplift_z_node(int k, int resolution) {
  if (k <= 0) return 0.0f;
  if (resolution <= 2) return 1.0f;
  const double t = static_cast<double>(k - 1) / (resolution - 2);
  return static_cast<float>(kUpliftDarkestFit + (1.0 - kUpliftDarkestFit) * smoothstep(t));
}

UpliftTableData build_uplift_table(int resolution, int threads) {
  UpliftTableData table;
  const int res = std::max(resolution, 2);
  table.resolution = res;
  table.z_nodes.resize(res);
  for (int k = 0; k < res; ++k) table.z_nodes[k] = uplift_z_node(k, res);
  table.coeffs.assign(static_cast<size_t>(3) * res * res * res * 3, 0.0f);
  const UpliftFitter fitter;

  // One job per (sheet, y row): every x column in it, the z cells of a column fitted outward
  // from z index res/3 (a mid-grey brightness whose fit from c = 0 converges), each from its
  // neighbour's solution. Layer 0 (black) is not fitted: RgbToSpectrumTable takes its spectrum
  // as exactly 0 and leaves its coefficients (zeros) unused.
  auto fit_row = [&](int job) {
    const int sheet = job / res, yi = job % res;
    for (int xi = 0; xi < res; ++xi) {
      const double x = static_cast<double>(xi) / (res - 1);
      const double y = static_cast<double>(yi) / (res - 1);
      const int start = std::max(1, res / 3);
      double c_start[3] = {0.0, 0.0, 0.0};
      auto fit_cell = [&](int zi, double c[3]) {
        const double z = table.z_nodes[zi];
        float rgb[3];
        rgb[sheet] = static_cast<float>(z);
        rgb[(sheet + 1) % 3] = static_cast<float>(x * z);
        rgb[(sheet + 2) % 3] = static_cast<float>(y * z);
        fitter.fit(Vec3(rgb[0], rgb[1], rgb[2]), c);
        float* out =
            &table.coeffs[((((static_cast<size_t>(sheet) * res + zi) * res + yi) * res + xi)) * 3];
        for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(c[k]);
      };
      fit_cell(start, c_start);
      double c[3];
      std::memcpy(c, c_start, sizeof(c));
      for (int zi = start + 1; zi < res; ++zi) fit_cell(zi, c);
      std::memcpy(c, c_start, sizeof(c));
      for (int zi = start - 1; zi >= 1; --zi) fit_cell(zi, c);
    }
  };

  const int jobs = 3 * res;
  const int n = std::clamp(threads, 1, jobs);
  std::vector<std::thread> pool;
  for (int t = 0; t < n; ++t)
    pool.emplace_back([&, t] {
      for (int job = t; job < jobs; job += n) fit_row(job);
    });
  for (auto& th : pool) th.join();
  return table;
}

bool write_uplift_table(const UpliftTableData& table, const char* path) {
  std::FILE* f = std::fopen(path, "wb");
  if (!f) return false;
  bool ok = std::fwrite("PHUPLFT1", 1, 8, f) == 8;
  ok = ok && std::fwrite(&table.resolution, sizeof(int32_t), 1, f) == 1;
  ok = ok && std::fwrite(table.z_nodes.data(), sizeof(float), table.z_nodes.size(), f) ==
                 table.z_nodes.size();
  ok = ok && std::fwrite(table.coeffs.data(), sizeof(float), table.coeffs.size(), f) ==
                 table.coeffs.size();
  return std::fclose(f) == 0 && ok;
}

}  // namespace photon::spectral

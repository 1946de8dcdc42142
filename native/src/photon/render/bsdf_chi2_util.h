// Test helpers shared by the BSDF unit tests: a seeded uniform generator and a chi-square
// goodness-of-fit test of a BSDF's sample() against its pdf() (after pbrt-v3's
// src/tests/bsdfs.cpp). Header-only; included by *_test.cpp files only.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "photon/base/rng.h"
#include "photon/render/bsdf.h"

namespace photon {
namespace bsdf_chi2 {

constexpr double kChi2Pi = 3.14159265358979323846;

class Uniform {
 public:
  explicit Uniform(uint64_t seed) : rng_(seed) {}
  float next() { return to_unit_float(rng_()); }
  Vec2 next_2d() {
    const float a = next();
    return {a, next()};
  }

 private:
  std::mt19937_64 rng_;
};

// ---- Chi-square goodness of fit (after pbrt-v3's src/tests/bsdfs.cpp) ----

// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes, sec. 6.2): series for
// x < a + 1, Lentz's continued fraction otherwise.
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double sum = 1.0 / a, term = sum;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(log_prefix);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

inline double chi2_p_value(double statistic, int dof) {
  return gamma_q(0.5 * dof, 0.5 * statistic);
}

struct Chi2Result {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  long outside_support = 0;  // samples in cells where the integrated pdf is zero
  double expected_total = 0.0;
  long observed_total = 0;
};

// Histograms directions over (theta, phi) of the local frame and compares the counts with
// expected counts from integrating `pdf` over every cell (composite Simpson on a sub-grid).
// Cells expecting fewer than 5 samples are pooled, smallest first.
struct Chi2Test {
  static constexpr int kTheta = 32, kPhi = 64;
  // Integration error allowed per cell, in expected samples: far below the Poisson noise.
  static constexpr double kTolerance = 0.02;
  int sample_count = 250000;

  // Integral of pdf(w) sin(theta) over a (theta, phi) rectangle by adaptive Simpson
  // quadrature: 4 x 4 Simpson against 2 x 2, quartering the rectangle where they disagree
  // (peaks of sharp lobes, kinks at the edge of a lobe's support).
  static double integrate(const std::function<double(const Vec3&)>& pdf, double t0, double t1,
                          double p0, double p1, double tol, int depth) {
    double f[5][5];
    for (int i = 0; i < 5; ++i) {
      const double theta = t0 + (t1 - t0) * i / 4.0, st = std::sin(theta), ct = std::cos(theta);
      for (int j = 0; j < 5; ++j) {
        const double phi = p0 + (p1 - p0) * j / 4.0;
        f[i][j] = pdf(Vec3(static_cast<float>(st * std::cos(phi)),
                           static_cast<float>(st * std::sin(phi)), static_cast<float>(ct))) *
                  st;
      }
    }
    const double w4[5] = {1, 4, 2, 4, 1}, w2[3] = {1, 4, 1};
    double fine = 0.0, coarse = 0.0;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) fine += w4[i] * w4[j] * f[i][j];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) coarse += w2[i] * w2[j] * f[2 * i][2 * j];
    const double area = (t1 - t0) * (p1 - p0);
    fine *= area / 144.0;
    coarse *= area / 36.0;
    if (std::fabs(fine - coarse) <= 15.0 * tol || depth >= 7) return fine + (fine - coarse) / 15.0;
    const double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
    return integrate(pdf, t0, tm, p0, pm, tol / 4, depth + 1) +
           integrate(pdf, tm, t1, p0, pm, tol / 4, depth + 1) +
           integrate(pdf, t0, tm, pm, p1, tol / 4, depth + 1) +
           integrate(pdf, tm, t1, pm, p1, tol / 4, depth + 1);
  }

  Chi2Result run(const std::function<bool(Uniform&, Vec3*)>& sample,
                 const std::function<double(const Vec3&)>& pdf, uint64_t seed,
                 bool renormalize_expected = false) const {
    std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
    Uniform rng(seed);
    Chi2Result r;
    for (int i = 0; i < sample_count; ++i) {
      Vec3 w;
      if (!sample(rng, &w)) continue;
      const double theta = std::acos(std::clamp(static_cast<double>(w.z), -1.0, 1.0));
      double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
      if (phi < 0.0) phi += 2.0 * kChi2Pi;
      const int t = std::clamp(static_cast<int>(theta / kChi2Pi * kTheta), 0, kTheta - 1);
      const int p = std::clamp(static_cast<int>(phi / (2.0 * kChi2Pi) * kPhi), 0, kPhi - 1);
      observed[t * kPhi + p] += 1.0;
      ++r.observed_total;
    }
    const double cell_t = kChi2Pi / kTheta, cell_p = 2.0 * kChi2Pi / kPhi;
    for (int t = 0; t < kTheta; ++t)
      for (int p = 0; p < kPhi; ++p)
        expected[t * kPhi + p] =
            sample_count * integrate(pdf, t * cell_t, (t + 1) * cell_t, p * cell_p,
                                     (p + 1) * cell_p, kTolerance / sample_count, 0);
    for (double e : expected) r.expected_total += e;
    if (renormalize_expected && r.expected_total > 0.0)
      for (double& e : expected) e *= r.observed_total / r.expected_total;

    std::vector<int> order(expected.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pooled_obs = 0.0, pooled_exp = 0.0;
    for (int c : order) {
      if (expected[c] == 0.0) {
        r.outside_support += static_cast<long>(observed[c]);
      } else if (expected[c] < 5.0 || (pooled_exp > 0.0 && pooled_exp < 5.0)) {
        pooled_obs += observed[c];
        pooled_exp += expected[c];
      } else {
        const double d = observed[c] - expected[c];
        r.statistic += d * d / expected[c];
        ++r.dof;
      }
    }
    if (pooled_exp > 0.0) {
      const double d = pooled_obs - pooled_exp;
      r.statistic += d * d / pooled_exp;
      ++r.dof;
    }
    r.dof -= 1;
    r.p_value = chi2_p_value(r.statistic, std::max(r.dof, 1));
    return r;
  }

  // sample() and pdf() of a BSDF at wo, histogrammed in its shading frame.
  Chi2Result run_bsdf(const Bsdf& b, const Vec3& wo, uint64_t seed,
                      const std::function<double(const Vec3&, double)>& pdf_transform = nullptr,
                      bool renormalize_expected = false) const {
    return run(
        [&](Uniform& rng, Vec3* w) {
          BsdfSample s;
          const float u_lobe = rng.next();
          const Vec2 u = rng.next_2d();
          if (!b.sample(wo, u_lobe, u, kLobeAll, &s) || s.is_delta()) return false;
          *w = b.frame().to_local(s.wi);
          return true;
        },
        [&](const Vec3& w_local) {
          const double p = b.pdf(wo, b.frame().to_world(w_local), kLobeAll);
          return pdf_transform ? pdf_transform(w_local, p) : p;
        },
        seed, renormalize_expected);
  }
};

// The direction `theta_deg` from b's shading normal, at azimuth `phi` in its frame.
inline Vec3 direction_at(const Bsdf& b, float theta_deg, float phi = 0.0f) {
  const float t = theta_deg * static_cast<float>(kChi2Pi / 180.0);
  return b.frame().to_world(
      Vec3(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)));
}

// `n` samples of b at wo: each non-delta one's pdf is pdf()'s and its weight eval() |cos| / pdf,
// to 1e-3. `checked` (if given) receives how many were compared.
inline ::testing::AssertionResult sample_weights_match(const Bsdf& b, const Vec3& wo, uint64_t seed,
                                                       int n, int* checked = nullptr) {
  Uniform rng(seed);
  int count = 0;
  for (int i = 0; i < n; ++i) {
    BsdfSample s;
    const float u_lobe = rng.next();
    if (!b.sample(wo, u_lobe, rng.next_2d(), kLobeAll, &s) || s.is_delta()) continue;
    const Vec3 f = b.eval(wo, s.wi);
    const float pdf = b.pdf(wo, s.wi);
    if (!(std::fabs(s.pdf - pdf) <= 1e-3f * pdf + 1e-6f))
      return ::testing::AssertionFailure()
             << "sample " << i << ": pdf " << s.pdf << ", pdf() " << pdf;
    const float cos = std::fabs(dot(s.wi, b.frame().n));
    for (int k = 0; k < 3; ++k) {
      const float want = f[k] * cos / pdf;
      if (!(std::fabs(s.weight[k] - want) <= 1e-3f * s.weight[k] + 1e-6f))
        return ::testing::AssertionFailure() << "sample " << i << " channel " << k << ": weight "
                                             << s.weight[k] << ", f |cos| / pdf " << want;
    }
    ++count;
  }
  if (checked) *checked = count;
  return ::testing::AssertionSuccess();
}

// Sidak correction: a suite of `tests` rejects a correct implementation with probability 0.01.
inline double sidak_significance(int tests) {
  return 1.0 - std::pow(1.0 - 0.01, 1.0 / tests);
}

}  // namespace bsdf_chi2
}  // namespace photon

#include "photon/base/spherical_caps.h"

#include <gtest/gtest.h>

#include <cmath>

#include "photon/base/rng.h"
#include "photon/base/sampling.h"

namespace photon {
namespace spherical_caps_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

Vec3 direction_at(double polar, double azimuth) {
  return Vec3(static_cast<float>(std::sin(polar) * std::cos(azimuth)),
              static_cast<float>(std::sin(polar) * std::sin(azimuth)),
              static_cast<float>(std::cos(polar)));
}

struct Case {
  const char* name;
  Cap a, b;
};

std::vector<Case> cases() {
  const Vec3 z(0, 0, 1);
  return {
      {"two small caps crossing", Cap(z, 0.2), Cap(direction_at(0.25, 1.0), 0.15)},
      {"narrow spot across a cone's rim", Cap(z, 0.0175), Cap(direction_at(0.2, 0.3), 0.19)},
      {"hemisphere and a wide cone", Cap(z, 0.5 * kPiD), Cap(direction_at(1.7, 2.0), 0.6)},
      {"nested", Cap(z, 0.5), Cap(direction_at(0.1, 0.0), 0.2)},
      {"large caps covering the sphere together", Cap(z, 2.5), Cap(direction_at(2.0, 0.5), 2.4)},
      {"whole sphere", Cap::whole_sphere(), Cap(direction_at(1.0, 1.0), 0.3)},
  };
}

// The closed-form overlap against counting uniform directions inside both caps (4 sigma).
TEST(SphericalCaps, OverlapMatchesMonteCarlo) {
  for (const Case& c : cases()) {
    const int n = 400000;
    int inside = 0;
    for (int i = 0; i < n; ++i) {
      Sampler s(7, 0, static_cast<uint32_t>(i));
      const Vec3 w = sample_uniform_sphere(s.get_2d());
      if (c.a.contains(w) && c.b.contains(w)) ++inside;
    }
    const double p = static_cast<double>(inside) / n;
    const double sigma = 4.0 * kPiD * std::sqrt(std::max(p * (1 - p), 1.0 / n) / n);
    EXPECT_NEAR(cap_overlap(c.a, c.b), 4.0 * kPiD * p, 4.0 * sigma) << c.name;
    EXPECT_NEAR(cap_overlap(c.a, c.b), cap_overlap(c.b, c.a), 1e-12) << c.name;
  }
  // Disjoint caps share nothing.
  EXPECT_EQ(cap_overlap(Cap(Vec3(0, 0, 1), 0.1), Cap(Vec3(1, 0, 0), 0.2)), 0.0);
}

// Samples lie in both caps and are uniform there: the share falling in a third cap that cuts the
// overlap equals the solid angle share, counted with uniform directions (4 sigma).
TEST(SphericalCaps, OverlapSamplesAreUniformInBothCaps) {
  for (const Case& c : cases()) {
    const double area = cap_overlap(c.a, c.b);
    // A probe cap centred on one sample, half the size of the smaller cap.
    Vec3 centre;
    ASSERT_TRUE(sample_cap_overlap(c.a, c.b, Vec2(0.3f, 0.6f), &centre)) << c.name;
    const Cap probe(centre, 0.5 * std::min(c.a.angle, c.b.angle));
    const int n = 200000;
    int in_probe = 0, outside = 0;
    for (int i = 0; i < n; ++i) {
      Sampler s(9, 0, static_cast<uint32_t>(i));
      Vec3 w;
      ASSERT_TRUE(sample_cap_overlap(c.a, c.b, s.get_2d(), &w)) << c.name;
      if (dot(w, c.a.axis) < c.a.cos_angle - 1e-5f || dot(w, c.b.axis) < c.b.cos_angle - 1e-5f)
        ++outside;
      if (probe.contains(w)) ++in_probe;
    }
    EXPECT_EQ(outside, 0) << c.name;
    // Reference share: uniform directions inside the probe cap, counted in the overlap.
    int ref_in = 0;
    for (int i = 0; i < n; ++i) {
      Sampler s(11, 0, static_cast<uint32_t>(i));
      Vec2 u = s.get_2d();
      const Vec3 w = Frame(probe.axis).to_world(sample_uniform_cone(u, probe.cos_angle));
      if (c.a.contains(w) && c.b.contains(w)) ++ref_in;
    }
    const double expected = probe.solid_angle() * ref_in / n / area;
    const double p = static_cast<double>(in_probe) / n;
    const double sigma = std::sqrt(p * (1 - p) / n + expected * expected / ref_in);
    EXPECT_NEAR(p, expected, 4.0 * sigma) << c.name;
    EXPECT_GT(p, 0.01) << c.name << ": the probe must cut the overlap for the test to mean much";
  }
}

}  // namespace
}  // namespace spherical_caps_test
}  // namespace photon

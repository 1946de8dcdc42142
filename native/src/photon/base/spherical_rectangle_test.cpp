// Spherical rectangle sampling (spherical_rectangle.h): its solid angle against the closed form
// and against integrating over the area, its points on the rectangle, and uniformity in solid
// angle (each quarter of the rectangle gets samples in proportion to its own solid angle).
#include "photon/base/spherical_rectangle.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "photon/base/rng.h"

namespace photon {
namespace spherical_rectangle_test {
namespace {

// Solid angle of a rectangle by integrating cos / r^2 over its area (midpoint rule).
double solid_angle_by_area(const Vec3& o, const Vec3& corner, const Vec3& ex, const Vec3& ey) {
  const int n = 400;
  const Vec3 normal = normalize(cross(ex, ey));
  const double cell = length(ex) * length(ey) / (static_cast<double>(n) * n);
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 p = corner + ex * ((i + 0.5f) / n) + ey * ((j + 0.5f) / n);
      const Vec3 d = p - o;
      const double r2 = length_squared(d);
      sum += std::fabs(dot(d, normal)) / (r2 * std::sqrt(r2)) * cell;
    }
  return sum;
}

TEST(SphericalRectangle, SolidAngleMatchesTheClosedFormHeadOn) {
  // Seen from distance d above its centre, a rectangle of half sizes a and b subtends
  // 4 asin(a b / sqrt((a^2 + d^2)(b^2 + d^2))).
  for (const auto& [a, b, d] :
       {std::array<double, 3>{0.5, 0.5, 1.0}, std::array<double, 3>{2.0, 0.3, 0.5},
        std::array<double, 3>{0.01, 0.02, 3.0}, std::array<double, 3>{10.0, 10.0, 0.1}}) {
    const Vec3 o(0.0f, 0.0f, static_cast<float>(d));
    const SphericalRectangle rect(o, Vec3(static_cast<float>(-a), static_cast<float>(-b), 0.0f),
                                  Vec3(static_cast<float>(2 * a), 0.0f, 0.0f),
                                  Vec3(0.0f, static_cast<float>(2 * b), 0.0f));
    const double exact = 4.0 * std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d)));
    EXPECT_NEAR(rect.solid_angle(), exact, 1e-5 * exact + 1e-9) << a << " " << b << " " << d;
  }
}

TEST(SphericalRectangle, SolidAngleMatchesTheAreaIntegralFromAnySide) {
  const Vec3 corner(-0.3f, 0.2f, 0.5f), ex(1.2f, 0.0f, 0.4f), ey(0.0f, 0.7f, 0.0f);
  for (const Vec3& o : {Vec3(0.1f, 0.4f, -1.0f), Vec3(2.0f, -1.0f, 3.0f), Vec3(0.0f, 0.5f, 0.4f)}) {
    const SphericalRectangle rect(o, corner, ex, ey);
    const double by_area = solid_angle_by_area(o, corner, ex, ey);
    EXPECT_NEAR(rect.solid_angle(), by_area, 1e-3 * by_area);
  }
}

TEST(SphericalRectangle, EmptyInItsPlaneOrWithoutArea) {
  EXPECT_TRUE(SphericalRectangle(Vec3(5.0f, 0.0f, 0.0f), Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f),
                                 Vec3(0.0f, 1.0f, 0.0f))
                  .empty());
  EXPECT_TRUE(
      SphericalRectangle(Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f))
          .empty());
}

TEST(SphericalRectangle, SamplesLieOnItAndAreUniformInSolidAngle) {
  const Vec3 o(0.4f, -0.3f, 0.35f);
  const Vec3 corner(-0.5f, -0.5f, 0.0f), ex(1.0f, 0.0f, 0.0f), ey(0.0f, 1.5f, 0.0f);
  const SphericalRectangle rect(o, corner, ex, ey);
  ASSERT_FALSE(rect.empty());
  // The four quarters' own solid angles.
  double quarter[4];
  for (int q = 0; q < 4; ++q) {
    const Vec3 c = corner + ex * (0.5f * (q & 1)) + ey * (0.5f * (q >> 1));
    quarter[q] = SphericalRectangle(o, c, ex * 0.5f, ey * 0.5f).solid_angle();
  }
  EXPECT_NEAR(quarter[0] + quarter[1] + quarter[2] + quarter[3], rect.solid_angle(),
              1e-4 * rect.solid_angle());
  const int n = 400000;
  int count[4] = {0, 0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(1, 0, static_cast<uint32_t>(i), n);
    const Vec3 p = rect.sample(sampler.get_2d());
    ASSERT_NEAR(p.z, 0.0f, 1e-5f);
    const float s = (p.x - corner.x) / ex.x, t = (p.y - corner.y) / ey.y;
    ASSERT_GE(s, -1e-5f);
    ASSERT_LE(s, 1.0f + 1e-5f);
    ASSERT_GE(t, -1e-5f);
    ASSERT_LE(t, 1.0f + 1e-5f);
    ++count[(s >= 0.5f ? 1 : 0) + (t >= 0.5f ? 2 : 0)];
  }
  for (int q = 0; q < 4; ++q) {
    const double expected = quarter[q] / rect.solid_angle();
    EXPECT_NEAR(static_cast<double>(count[q]) / n, expected, 0.005) << "quarter " << q;
  }
}

}  // namespace
}  // namespace spherical_rectangle_test
}  // namespace photon

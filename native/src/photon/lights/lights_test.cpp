#include "photon/lights/lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "photon/testing/test_scenes.h"

namespace photon {
namespace lights_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

::testing::AssertionResult VecNear(const Vec3& a, const Vec3& b, float rel_tol) {
  const float d = length(a - b);
  if (d <= rel_tol * std::max(1e-12f, length(b))) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") vs ("
                                       << b.x << ", " << b.y << ", " << b.z << "), distance " << d;
}

Light make_light(LightType type, const Vec3& position, float power) {
  Light l;
  l.name = "test_light";
  l.type = type;
  l.light_to_world = Transform::translation(position);  // identity rotation: emits down world -Z
  l.power = power;
  return l;
}

// Mean of f(sample) over an n x n grid of stratum midpoints; counts failed samples as zero.
Vec3 average_over_grid(const LightSet& set, size_t index, const Vec3& p, int n,
                       const std::function<Vec3(const LightSample&)>& f) {
  Vec3 sum(0.0f);
  double sx = 0, sy = 0, sz = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      LightSample ls;
      if (!set.lamp(index).sample_li(p, LightSampleU{0.0f, Vec2((i + 0.5f) / n, (j + 0.5f) / n)},
                                     nullptr, &ls))
        continue;
      const Vec3 v = f(ls);
      sx += v.x;
      sy += v.y;
      sz += v.z;
    }
  const double inv = 1.0 / (static_cast<double>(n) * n);
  sum = Vec3(static_cast<float>(sx * inv), static_cast<float>(sy * inv),
             static_cast<float>(sz * inv));
  return sum;
}

TEST(PointLight, IrradianceFollowsTheInverseSquareLaw) {
  Light light = make_light(LightType::kPoint, Vec3(1.0f, -2.0f, 3.0f), 100.0f);
  light.color = Vec3(1.0f, 0.5f, 0.25f);
  std::vector<std::string> warnings;
  LightSet set({light}, &warnings);
  ASSERT_EQ(set.size(), 1u);
  EXPECT_TRUE(warnings.empty());
  const double intensity = 100.0 / (4.0 * kPiD);  // W/sr
  // Straight below, and at an angle (a point light has no cosine falloff of its own).
  for (const Vec3& p : {Vec3(1.0f, -2.0f, 0.0f), Vec3(5.0f, -2.0f, 0.0f), Vec3(1.0f, 1.0f, 7.0f)}) {
    LightSample ls;
    ASSERT_TRUE(set.lamp(0).sample_li(p, LightSampleU{0.0f, Vec2(0.3f, 0.7f)}, nullptr, &ls));
    const Vec3 to_light = light.light_to_world.column(3) - p;
    const float d2 = length_squared(to_light);
    EXPECT_NEAR(ls.distance, std::sqrt(d2), 1e-5f);
    EXPECT_TRUE(VecNear(ls.wi, to_light / std::sqrt(d2), 1e-6f));
    EXPECT_TRUE(VecNear(ls.weight, light.color * static_cast<float>(intensity / d2), 1e-5f));
  }
}

TEST(PointLight, SphereLightConvergesToThePointLightFarAway) {
  const float d = 5.0f, r = 0.05f, power = 30.0f;
  Light light = make_light(LightType::kPoint, Vec3(0.0f, 0.0f, d), power);
  light.radius = r;
  LightSet set({light}, nullptr);
  const Vec3 p(0.0f);
  const Vec3 mean = average_over_grid(set, 0, p, 200, [&](const LightSample& ls) {
    // Every sample lies on the disc of radius r through the centre, facing the point.
    const Vec3 q = p + ls.wi * ls.distance;
    EXPECT_LE(length(q - light.light_to_world.column(3)), r * 1.0001f);
    EXPECT_NEAR(q.z, d, 1e-5f);
    return ls.weight;
  });
  const double point = power / (4.0 * kPiD * d * d);
  EXPECT_NEAR(mean.x, point, 1e-3 * point);
  // Exactly: mean of I cos_l / dist^2 over the disc = (2 I / r^2) (1 - d / sqrt(d^2 + r^2)).
  const double intensity = power / (4.0 * kPiD);
  const double exact =
      2.0 * intensity / (r * r) * (1.0 - d / std::sqrt(double(d) * d + double(r) * r));
  EXPECT_NEAR(mean.y, exact, 2e-4 * exact);
}

TEST(PointLight, SphereLightIrradianceNearbyMatchesADisc) {
  // Irradiance on axis from a uniform disc of radiance L = I / (pi r^2) at distance d, facing
  // the receiver: E = pi L r^2 / (d^2 + r^2) = I / (d^2 + r^2).
  const float d = 2.0f, r = 0.5f, power = 30.0f;
  Light light = make_light(LightType::kPoint, Vec3(0.0f, 0.0f, d), power);
  light.radius = r;
  LightSet set({light}, nullptr);
  const Vec3 e = average_over_grid(set, 0, Vec3(0.0f), 256,
                                   [](const LightSample& ls) { return ls.weight * ls.wi.z; });
  const double expected = power / (4.0 * kPiD) / (d * d + r * r);
  EXPECT_NEAR(e.x, expected, 1e-3 * expected);
  EXPECT_GT(std::fabs(e.x - power / (4.0 * kPiD) / (d * d)),
            0.03 * expected);  // not the point value
}

TEST(SpotLight, IsZeroOutsideTheConeAndCosineWeightedInside) {
  const float power = 50.0f, d = 2.0f;
  Light light = make_light(LightType::kSpot, Vec3(0.0f, 0.0f, d), power);
  light.spot_size = kPi / 3.0f;  // 30 degree half angle
  light.spot_blend = 0.2f;
  LightSet set({light}, nullptr);
  const double intensity = power / (4.0 * kPiD);
  const double cos_half = std::cos(kPiD / 6.0);
  const double smooth = (1.0 - cos_half) * 0.2;
  auto receiver_at = [&](double angle) {  // on the floor, `angle` away from the spot axis
    return Vec3(static_cast<float>(d * std::tan(angle)), 0.0f, 0.0f);
  };
  auto weight_at = [&](double angle) {
    LightSample ls;
    if (!set.lamp(0).sample_li(receiver_at(angle), LightSampleU{0.0f, Vec2(0.5f, 0.5f)}, nullptr,
                               &ls))
      return 0.0;
    return static_cast<double>(ls.weight.x);
  };
  // On the axis: the point light value.
  EXPECT_NEAR(weight_at(0.0), intensity / (d * d), 1e-5 * intensity);
  // Inside the cone, past the blend: point value times the cosine to the axis.
  for (double deg : {5.0, 15.0, 20.0}) {
    const double a = deg * kPiD / 180.0, c = std::cos(a);
    ASSERT_GT(c - cos_half, smooth);
    const double dist2 = (d / c) * (d / c);
    EXPECT_NEAR(weight_at(a), intensity / dist2 * c, 1e-5 * intensity) << deg;
  }
  // Outside the cone nothing arrives.
  for (double deg : {30.5, 45.0, 80.0}) {
    LightSample ls;
    EXPECT_FALSE(set.lamp(0).sample_li(receiver_at(deg * kPiD / 180.0),
                                       LightSampleU{0.0f, Vec2(0.5f, 0.5f)}, nullptr, &ls))
        << deg;
  }
  LightSample ls;
  EXPECT_FALSE(set.lamp(0).sample_li(
      Vec3(0.0f, 0.0f, 2.0f * d), LightSampleU{0.0f, Vec2(0.5f, 0.5f)}, nullptr, &ls));  // behind

  // Blend region: smoothstep in (cos - cos_half) / smooth, halfway = half of the full value.
  const double c_mid = cos_half + 0.5 * smooth, a_mid = std::acos(c_mid);
  EXPECT_NEAR(weight_at(a_mid), intensity * c_mid * c_mid * c_mid / (d * d) * 0.5,
              1e-4 * intensity);
  // Continuous and monotonic from the cone edge to the end of the blend.
  const double a_edge = std::acos(cos_half), a_full = std::acos(cos_half + smooth);
  double previous = 0.0;
  for (int k = 0; k <= 50; ++k) {
    const double a = a_edge + (a_full - a_edge) * k / 50.0;
    const double w = weight_at(a);
    EXPECT_GE(w, previous - 1e-7 * intensity) << k;
    EXPECT_LT(w - previous, 0.1 * intensity / (d * d)) << k;  // no jumps
    previous = w;
  }
  const double c_full = std::cos(a_full);
  EXPECT_NEAR(previous, intensity * c_full * c_full * c_full / (d * d), 1e-3 * intensity);
}

TEST(SpotLight, WithoutTheCosineFalloffIsThePointValueInsideTheCone) {
  // Cycles 4.0+: only the blend's smoothstep shapes the cone, and the power is still I * 4 pi
  // spread over the whole sphere (the cone keeps the point light's intensity).
  const float power = 50.0f, d = 2.0f;
  Light light = make_light(LightType::kSpot, Vec3(0.0f, 0.0f, d), power);
  light.spot_size = kPi / 3.0f;
  light.spot_blend = 0.2f;
  light.spot_cosine_falloff = false;
  LightSet set({light}, nullptr);
  const double intensity = power / (4.0 * kPiD);
  const double cos_half = std::cos(kPiD / 6.0), smooth = (1.0 - cos_half) * 0.2;
  auto weight_at = [&](double angle) {
    const Vec3 p(static_cast<float>(d * std::tan(angle)), 0.0f, 0.0f);
    LightSample ls;
    if (!set.lamp(0).sample_li(p, LightSampleU{0.0f, Vec2(0.5f, 0.5f)}, nullptr, &ls)) return 0.0;
    return static_cast<double>(ls.weight.x);
  };
  for (double deg : {0.0, 10.0, 20.0}) {
    const double a = deg * kPiD / 180.0, c = std::cos(a);
    EXPECT_NEAR(weight_at(a), intensity * c * c / (d * d), 1e-5 * intensity) << deg;
  }
  const double c_mid = cos_half + 0.5 * smooth;
  EXPECT_NEAR(weight_at(std::acos(c_mid)), intensity * c_mid * c_mid / (d * d) * 0.5,
              1e-4 * intensity);
  EXPECT_EQ(weight_at(31.0 * kPiD / 180.0), 0.0);
}

TEST(SpotLight, PointsAlongTheTransformedAxis) {
  // Rotation of +90 degrees about x: local -Z becomes world +Y.
  Light light = make_light(LightType::kSpot, Vec3(0.0f), 10.0f);
  const float rows[12] = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0};
  light.light_to_world = Transform::from_rows(rows);
  light.spot_size = 1.0f;
  LightSet set({light}, nullptr);
  LightSample ls;
  ASSERT_TRUE(set.lamp(0).sample_li(Vec3(0.0f, 3.0f, 0.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)},
                                    nullptr, &ls));
  EXPECT_NEAR(ls.weight.x, 10.0 / (4.0 * kPiD) / 9.0, 1e-6);
  EXPECT_FALSE(set.lamp(0).sample_li(Vec3(0.0f, -3.0f, 0.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)},
                                     nullptr, &ls));
  EXPECT_FALSE(set.lamp(0).sample_li(Vec3(0.0f, 0.0f, -3.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)},
                                     nullptr, &ls));
  EXPECT_FALSE(set.lamp(0).sample_li(Vec3(3.0f, 0.0f, 0.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)},
                                     nullptr, &ls));
}

TEST(SunLight, GivesItsStrengthFromWithinItsAngularDisc) {
  const Vec3 forward = normalize(Vec3(1.0f, -2.0f, -3.0f));  // direction the light travels
  Light light;
  light.type = LightType::kSun;
  light.light_to_world = make_look_at_camera(Vec3(4, 5, 6), Vec3(4, 5, 6) + forward, 1.0f, 1.0f)
                             .camera_to_world;  // local -Z = forward
  light.power = 3.0f;
  light.color = Vec3(1.0f, 0.9f, 0.8f);
  light.sun_angle = 0.1f;
  LightSet set({light}, nullptr);
  const double cos_max = std::cos(0.05);
  double widest = 0.0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      LightSample ls;
      ASSERT_TRUE(set.lamp(0).sample_li(Vec3(0.3f, 0.2f, 0.1f),
                                        LightSampleU{0.0f, Vec2((i + 0.5f) / 32, (j + 0.5f) / 32)},
                                        nullptr, &ls));
      EXPECT_FALSE(std::isfinite(ls.distance));
      EXPECT_TRUE(VecNear(ls.weight, light.color * 3.0f, 1e-6f));
      EXPECT_NEAR(length(ls.wi), 1.0f, 1e-5f);
      const double c = dot(ls.wi, -forward);
      EXPECT_GE(c, cos_max - 1e-6);
      widest = std::max(widest, std::acos(std::min(1.0, c)));
    }
  EXPECT_GT(widest, 0.9 * 0.05);  // the disc is used, not just its centre

  // Without an angle, the sun is a single direction.
  light.sun_angle = 0.0f;
  LightSet sharp({light}, nullptr);
  LightSample ls;
  ASSERT_TRUE(
      sharp.lamp(0).sample_li(Vec3(0.0f), LightSampleU{0.0f, Vec2(0.9f, 0.1f)}, nullptr, &ls));
  EXPECT_TRUE(VecNear(ls.wi, -forward, 1e-6f));
}

TEST(SunLight, VisibleDiscRadianceIntegratesToTheStrength) {
  // A disc of directions of half angle a and uniform radiance L gives E = pi L sin^2(a) at normal
  // incidence; Cycles' radiance S / (pi tan^2 a) makes that S cos^2 a, i.e. S for a small disc.
  Light light = make_light(LightType::kSun, Vec3(0.0f), 2.0f);
  light.sun_angle = 0.05f;
  light.visibility = kVisibleAll;
  LightSet set({light}, nullptr);
  // The sun is at infinity: rays that leave the scene see it, whatever their clip distance.
  const Vec3 radiance = set.distant_radiance(Vec3(0, 0, 1), kVisibleCamera);
  EXPECT_NEAR(kPiD * radiance.x * std::sin(0.025) * std::sin(0.025), 2.0, 3e-3);
  // Outside the disc, or for rays the sun is hidden from, nothing.
  EXPECT_EQ(set.distant_radiance(normalize(Vec3(0.1f, 0, 1)), kVisibleCamera).x, 0.0f);
  light.visibility = kVisibleGlossy;
  LightSet hidden({light}, nullptr);
  EXPECT_EQ(hidden.distant_radiance(Vec3(0, 0, 1), kVisibleCamera).x, 0.0f);
  EXPECT_GT(hidden.distant_radiance(Vec3(0, 0, 1), kVisibleGlossy).x, 0.0f);
  // Finite-distance intersection never reports the sun.
  Ray ray;
  ray.direction = Vec3(0, 0, 1);
  float t;
  Vec3 le;
  EXPECT_FALSE(set.intersect(ray, INFINITY, kVisibleCamera, &t, &le));
}

// Sum over two corners of int int h^2 / (x^2 + y^2 + h^2)^2 over [0, a] x [0, b] (the point below
// a corner of an a x b rectangle at height h): (1/2) F(a, b) with
// F = a / sqrt(a^2 + h^2) atan(b / sqrt(a^2 + h^2)) + b / sqrt(b^2 + h^2) atan(a / sqrt(b^2 +
// h^2)).
double corner_integral(double a, double b, double h) {
  const double sa = std::sqrt(a * a + h * h), sb = std::sqrt(b * b + h * h);
  return 0.5 * (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb));
}

TEST(AreaLight, CornerIntegralClosedFormMatchesQuadrature) {
  // The closed form used below, checked against a direct midpoint quadrature and against the
  // infinite-plane limit (a quarter plane gives pi / 4, so E = pi L for an infinite emitter).
  for (const auto& abh : {std::vector<double>{0.6, 0.3, 0.8}, std::vector<double>{1.0, 2.0, 0.5}}) {
    const double a = abh[0], b = abh[1], h = abh[2];
    const int n = 1500;
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) * a / n, y = (j + 0.5) * b / n;
        const double r2 = x * x + y * y + h * h;
        sum += h * h / (r2 * r2);
      }
    sum *= (a / n) * (b / n);
    EXPECT_NEAR(corner_integral(a, b, h), sum, 1e-6);
  }
  EXPECT_NEAR(corner_integral(1e7, 1e7, 1.0), kPiD / 4.0, 1e-6);
}

TEST(AreaLight, IrradianceUnderARectangleMatchesTheClosedForm) {
  const float h = 0.8f, sx = 1.2f, sy = 0.6f, power = 20.0f;
  Light light = make_light(LightType::kArea, Vec3(0.0f, 0.0f, h), power);
  light.size_x = sx;
  light.size_y = sy;
  LightSet set({light}, nullptr);
  ASSERT_EQ(set.size(), 1u);
  const double radiance = power / (4.0 * sx * sy);  // L = P / (4 A)
  // Receivers facing up at x0 below the light: split the rectangle at the foot point into four
  // corner rectangles: E = L [F(a' - x0, b') + F(a' + x0, b')] with F = 2 corner_integral.
  const double ah = sx / 2.0, bh = sy / 2.0;
  for (double x0 : {0.0, 0.3}) {
    const Vec3 p(static_cast<float>(x0), 0.0f, 0.0f);
    const Vec3 e = average_over_grid(set, 0, p, 256, [](const LightSample& ls) {
      return ls.weight * std::max(0.0f, ls.wi.z);  // receiver cosine
    });
    const double expected =
        2.0 * radiance * (corner_integral(ah - x0, bh, h) + corner_integral(ah + x0, bh, h));
    EXPECT_NEAR(e.x, expected, 2e-3 * expected) << "x0 = " << x0;
  }
}

TEST(AreaLight, IrradianceUnderADiscMatchesTheClosedForm) {
  const float h = 0.7f, radius = 0.4f, power = 12.0f;
  Light light = make_light(LightType::kArea, Vec3(0.0f, 0.0f, h), power);
  light.shape = AreaShape::kEllipse;
  light.size_x = light.size_y = 2.0f * radius;
  LightSet set({light}, nullptr);
  const double radiance = power / (4.0 * kPiD * radius * radius);
  const Vec3 e = average_over_grid(set, 0, Vec3(0.0f), 256, [](const LightSample& ls) {
    return ls.weight * std::max(0.0f, ls.wi.z);
  });
  const double expected = kPiD * radiance * radius * radius / (h * h + radius * radius);
  EXPECT_NEAR(e.x, expected, 2e-3 * expected);
}

// With a spread, direct lighting samples only the part of a rectangle that reaches the
// receiver: its irradiance is still that of the radiance a ray meets (quadrature over
// eval_li), and eval_li reports the density its samples have.
TEST(AreaLight, SpreadIrradianceMatchesQuadratureAndSampleDensities) {
  for (AreaShape shape : {AreaShape::kRectangle, AreaShape::kEllipse})
    for (float degrees : {3.0f, 30.0f, 90.0f}) {
      Light light = make_light(LightType::kArea, Vec3(0.0f, 0.0f, 1.0f), 40.0f);
      light.shape = shape;
      light.size_x = 2.0f;
      light.size_y = 1.2f;
      light.spread = degrees * kPi / 180.0f;
      LightSet set({light}, nullptr);
      const Emitter& e = set.lamp(0);
      for (const Vec3& p : {Vec3(0.0f, 0.0f, 0.0f), Vec3(0.7f, -0.3f, 0.2f)}) {
        // Midpoint quadrature over the lamp (facing down, centred above the origin) of the
        // radiance a ray meets, for a receiver facing up.
        double expected = 0.0;
        const int steps = 1500;
        for (int j = 0; j < steps; ++j)
          for (int i = 0; i < steps; ++i) {
            const double u = (i + 0.5) / steps - 0.5, v = (j + 0.5) / steps - 0.5;
            if (shape == AreaShape::kEllipse && 4.0 * (u * u + v * v) > 1.0) continue;
            const Vec3 d = Vec3(static_cast<float>(u * 2.0), static_cast<float>(v * 1.2), 1.0f) - p;
            const double d2 = length_squared(d);
            const Vec3 w = d / std::sqrt(static_cast<float>(d2));
            LightHit h;
            if (e.eval_li(p, w, &h)) expected += h.radiance.x * w.z * w.z / d2;
          }
        expected *= 2.0 * 1.2 / (static_cast<double>(steps) * steps);
        ASSERT_GT(expected, 0.0);
        const Vec3 got = average_over_grid(set, 0, p, 256, [](const LightSample& ls) {
          return ls.weight * std::max(0.0f, ls.wi.z);
        });
        EXPECT_NEAR(got.x, expected, 3e-3 * expected) << degrees << " at " << p.x;
        for (int k = 0; k < 16; ++k) {
          LightSample ls;
          if (!e.sample_li(p, LightSampleU{0.0f, Vec2((k % 4 + 0.5f) / 4, (k / 4 + 0.5f) / 4)},
                           nullptr, &ls))
            continue;
          LightHit h;
          ASSERT_TRUE(e.eval_li(p, ls.wi, &h));
          EXPECT_NEAR(h.pdf, ls.pdf, 1e-3f * ls.pdf);
          EXPECT_TRUE(VecNear(h.radiance * (1.0f / h.pdf), ls.weight, 1e-3f));
        }
      }
    }
}

TEST(AreaLight, EmitsOnlyDownItsAxis) {
  Light light = make_light(LightType::kArea, Vec3(0.0f, 0.0f, 1.0f), 20.0f);
  LightSet set({light}, nullptr);
  for (const Vec3& p : {Vec3(0.0f, 0.0f, 2.0f), Vec3(0.1f, -0.2f, 1.5f), Vec3(3.0f, 0.0f, 1.0f)}) {
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        LightSample ls;
        EXPECT_FALSE(set.lamp(0).sample_li(
            p, LightSampleU{0.0f, Vec2((i + 0.5f) / 16, (j + 0.5f) / 16)}, nullptr, &ls))
            << p.x << " " << p.y << " " << p.z;
      }
  }
  LightSample ls;
  EXPECT_TRUE(set.lamp(0).sample_li(Vec3(3.0f, 0.0f, 0.5f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)},
                                    nullptr, &ls));
}

TEST(LightSet, SkipsZeroSizeAndZeroPowerLights) {
  Light area = make_light(LightType::kArea, Vec3(0.0f, 0.0f, 1.0f), 20.0f);
  area.name = "flat_area";
  area.size_x = 0.0f;
  Light dark = make_light(LightType::kPoint, Vec3(0.0f, 0.0f, 1.0f), 0.0f);
  Light negative = make_light(LightType::kPoint, Vec3(0.0f, 0.0f, 1.0f), -5.0f);
  Light black = make_light(LightType::kSpot, Vec3(0.0f, 0.0f, 1.0f), 5.0f);
  black.color = Vec3(0.0f);
  Light good = make_light(LightType::kPoint, Vec3(0.0f, 0.0f, 2.0f), 8.0f);
  std::vector<std::string> warnings;
  LightSet set({area, dark, negative, good, black}, &warnings);
  ASSERT_EQ(set.size(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("flat_area"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("zero size"), std::string::npos) << warnings[0];
  LightSample ls;
  ASSERT_TRUE(
      set.lamp(0).sample_li(Vec3(0.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)}, nullptr, &ls));
  EXPECT_NEAR(ls.weight.x, 8.0 / (4.0 * kPiD) / 4.0, 1e-6);  // the surviving light is `good`

  Light broken = good;
  broken.power = std::nanf("");
  warnings.clear();
  LightSet none({broken}, &warnings);
  EXPECT_EQ(none.size(), 0u);
  EXPECT_EQ(warnings.size(), 1u);
}

TEST(LightSet, IntersectSeesAnAreaLightFromTheFrontOnly) {
  const float h = 1.0f, power = 20.0f;
  Light light = make_light(LightType::kArea, Vec3(0.0f, 0.0f, h), power);
  LightSet set({light}, nullptr);
  const float radiance = power / 4.0f;  // unit square
  float t = 0.0f;
  Vec3 le;
  Ray up;
  up.origin = Vec3(0.1f, 0.2f, 0.0f);
  up.direction = Vec3(0, 0, 1);
  ASSERT_TRUE(set.intersect(up, INFINITY, kVisibleGlossy, &t, &le));
  EXPECT_NEAR(t, h, 1e-6f);
  EXPECT_TRUE(VecNear(le, Vec3(radiance), 1e-6f));
  // Lamps are hidden from camera rays by default, as in Blender.
  EXPECT_FALSE(set.intersect(up, INFINITY, kVisibleCamera, &t, &le));
  // Too short, or aimed past the edge.
  EXPECT_FALSE(set.intersect(up, 0.99f * h, kVisibleGlossy, &t, &le));
  Ray outside = up;
  outside.origin = Vec3(0.6f, 0.0f, 0.0f);
  EXPECT_FALSE(set.intersect(outside, INFINITY, kVisibleGlossy, &t, &le));
  // Oblique ray into the front face.
  Ray oblique;
  oblique.origin = Vec3(-1.0f, 0.0f, 0.0f);
  oblique.direction = normalize(Vec3(1.2f, 0.1f, 1.0f));
  ASSERT_TRUE(set.intersect(oblique, INFINITY, kVisibleGlossy, &t, &le));
  EXPECT_NEAR(t, h / oblique.direction.z, 1e-5f);
  // From behind: the back is dark and the ray passes through.
  Ray down;
  down.origin = Vec3(0.1f, 0.2f, 2.0f);
  down.direction = Vec3(0, 0, -1);
  EXPECT_FALSE(set.intersect(down, INFINITY, kVisibleGlossy, &t, &le));
}

}  // namespace
}  // namespace lights_test
}  // namespace photon

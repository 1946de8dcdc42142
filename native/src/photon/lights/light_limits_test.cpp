// Absurd light settings are clamped to emitter_range() with a warning, and the photon density
// floor of the gather radius measures what it claims.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "photon/integrators/photon_map/photon_map.h"
#include "photon/lights/lights.h"
#include "photon/scene/material.h"

namespace photon {
namespace light_limits_test {
namespace {

Light lamp(LightType type, float power) {
  Light l;
  l.name = "Lamp";
  l.type = type;
  l.light_to_world = Transform::translation(Vec3(0.0f, 0.0f, 2.0f));
  l.power = power;
  l.size_x = l.size_y = 0.5f;
  return l;
}

TEST(LightLimits, HugePowerIsClampedToTheEmitterBoundWithAWarning) {
  const float hi = emitter_range().hi;
  for (LightType type : {LightType::kPoint, LightType::kSpot, LightType::kSun, LightType::kArea}) {
    std::vector<std::string> warnings;
    const LightSet set({lamp(type, 3e38f)}, &warnings);
    ASSERT_EQ(set.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("3e+38"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("clamped to 1e+12"), std::string::npos) << warnings[0];
    // The clamped lamp is the 1e12 one exactly, and every sample of it is finite.
    const LightSet bound({lamp(type, hi)}, nullptr);
    const Vec3 power = set.lamp(0).power(10.0f);
    EXPECT_TRUE(is_finite(power));
    EXPECT_EQ(power.x, bound.lamp(0).power(10.0f).x);
    LightSample s;
    ASSERT_TRUE(set.lamp(0).sample_li(Vec3(0.0f, 0.0f, 0.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)},
                                      nullptr, &s));
    EXPECT_TRUE(is_finite(s.weight));
    EXPECT_GT(s.weight.x, 0.0f);
  }
}

TEST(LightLimits, ColourTimesPowerOverflowingAFloatKeepsTheHue) {
  Light l = lamp(LightType::kArea, 3e38f);
  l.color = Vec3(4.0f, 2.0f, 1.0f);  // 1.2e39 in red: infinite as a float product
  std::vector<std::string> warnings;
  const LightSet set({l}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  const Vec3 power = set.lamp(0).power(1.0f);
  ASSERT_TRUE(is_finite(power));
  // Red carries the bound: the flux of a white lamp of that power.
  const float bound =
      LightSet({lamp(LightType::kArea, emitter_range().hi)}, nullptr).lamp(0).power(1.0f).x;
  EXPECT_NEAR(power.x, bound, 1e-6 * bound);
  EXPECT_NEAR(power.y / power.x, 0.5f, 1e-6f);
  EXPECT_NEAR(power.z / power.x, 0.25f, 1e-6f);
}

TEST(LightLimits, PowersWithinTheBoundAreKeptSilently) {
  std::vector<std::string> warnings;
  const LightSet set({lamp(LightType::kArea, 1e9f)}, &warnings);
  EXPECT_TRUE(warnings.empty());
  const LightSet unit({lamp(LightType::kArea, 1.0f)}, nullptr);
  EXPECT_FLOAT_EQ(set.lamp(0).power(1.0f).x / unit.lamp(0).power(1.0f).x, 1e9f);
}

TEST(LightLimits, PointRadiusWhoseDiscUnderflowsIsAPoint) {
  Light l = lamp(LightType::kPoint, 100.0f);
  l.radius = 1e-30f;  // pi r^2 = 3e-60: zero as a float
  const LightSet set({l}, nullptr);
  EXPECT_FALSE(set.lamp(0).has_area());
  LightSample s;
  ASSERT_TRUE(set.lamp(0).sample_li(Vec3(0.0f), LightSampleU{0.0f, Vec2(0.5f, 0.5f)}, nullptr, &s));
  EXPECT_TRUE(is_finite(s.weight));
  EXPECT_NEAR(s.weight.x, 100.0f / (4.0f * 3.14159265f * 4.0f), 1e-4f);
}

// Photons on a square grid of spacing h: the disc holding k of them has pi r^2 ~ k h^2.
TEST(LightLimits, MedianKthDistanceMatchesTheGridDensity) {
  const float h = 0.01f;
  std::vector<Photon> photons;
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 200; ++i)
      photons.push_back(Photon::make(Vec3(i * h, j * h, 0.0f), Vec3(0, 0, -1), Vec3(1e-3f),
                                     kPhotonIndirect, Vec3(0, 0, 1)));
  const PhotonMap map(std::move(photons));
  for (size_t k : {10u, 100u}) {
    const float expected = h * std::sqrt(static_cast<float>(k) / 3.14159265f);
    // Grid points come in rings, so the k-th distance is within a ring of the continuum value;
    // photons near the border (few among 40,000) see a larger one.
    EXPECT_NEAR(map.median_kth_distance(k, kPhotonAny), expected, 0.2f * expected) << k;
  }
  EXPECT_EQ(map.median_kth_distance(100, kPhotonCaustic), 0.0f);  // no caustic photons
  EXPECT_EQ(PhotonMap().median_kth_distance(10, kPhotonAny), 0.0f);
}

}  // namespace
}  // namespace light_limits_test
}  // namespace photon

#include "photon/base/optics.h"

#include <gtest/gtest.h>

namespace photon {
namespace optics_test {
namespace {

TEST(Fresnel, NormalIncidenceMatchesSchlickR0) {
  const float eta = 1.5f;
  const float r0 = ((eta - 1) / (eta + 1)) * ((eta - 1) / (eta + 1));
  EXPECT_NEAR(fresnel_dielectric(1.0f, eta), r0, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f / eta), r0, 1e-6f);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
  EXPECT_NEAR(fresnel_dielectric(1e-6f, 1.5f), 1.0f, 1e-3f);
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
  const float eta = 1.0f / 1.5f;  // glass to air
  const float critical = std::asin(eta);
  EXPECT_EQ(fresnel_dielectric(std::cos(critical + 0.01f), eta), 1.0f);
  EXPECT_LT(fresnel_dielectric(std::cos(critical - 0.05f), eta), 1.0f);
  Vec3 wt;
  const Vec3 n(0, 0, 1);
  const float a = critical + 0.01f;
  EXPECT_FALSE(refract(Vec3(std::sin(a), 0, std::cos(a)), n, eta, &wt));
}

TEST(Refract, ObeysSnellsLaw) {
  const Vec3 n(0, 0, 1);
  const float eta = 1.33f;
  for (float deg : {0.0f, 10.0f, 30.0f, 60.0f, 85.0f}) {
    const float a = deg * kPi / 180.0f;
    const Vec3 wi(std::sin(a), 0, std::cos(a));
    Vec3 wt;
    ASSERT_TRUE(refract(wi, n, eta, &wt));
    EXPECT_NEAR(length(wt), 1.0f, 1e-5f);
    EXPECT_LT(wt.z, 0.0f);  // goes through the surface
    EXPECT_LE(wt.x, 0.0f);  // and continues on the other side of the normal
    const float sin_t = std::sqrt(wt.x * wt.x + wt.y * wt.y);
    EXPECT_NEAR(std::sin(a), eta * sin_t, 1e-5f);  // n1 sin(i) = n2 sin(t)
  }
}

TEST(Reflect, MirrorsAboutTheNormal) {
  const Vec3 r = reflect(normalize(Vec3(1, 2, 3)), Vec3(0, 0, 1));
  const Vec3 e = normalize(Vec3(-1, -2, 3));
  EXPECT_NEAR(r.x, e.x, 1e-6f);
  EXPECT_NEAR(r.y, e.y, 1e-6f);
  EXPECT_NEAR(r.z, e.z, 1e-6f);
}

}  // namespace
}  // namespace optics_test
}  // namespace photon

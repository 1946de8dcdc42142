#include "photon/render/valid_reflection.h"

#include <gtest/gtest.h>

#include <cmath>

namespace photon {
namespace valid_reflection_test {
namespace {

Vec3 reflect_about(const Vec3& n, const Vec3& i) {
  return n * (2.0f * dot(n, i)) - i;
}

Vec3 unit(float x, float y, float z) {
  return normalize(Vec3(x, y, z));
}

TEST(ValidReflection, KeepsNormalsWhoseReflectionIsAboveTheSurface) {
  const Vec3 ng(0.0f, 0.0f, 1.0f);
  const Vec3 i = unit(0.3f, 0.1f, 1.0f);
  const Vec3 n = unit(-0.2f, 0.1f, 1.0f);
  const Vec3 out = ensure_valid_reflection(ng, i, n);
  EXPECT_EQ(out.x, n.x);
  EXPECT_EQ(out.y, n.y);
  EXPECT_EQ(out.z, n.z);
}

TEST(ValidReflection, BendsANormalFacingAwayFromTheViewerUntilTheReflectionGrazes) {
  // A grazing view and a bump normal tilted away from it: its mirror reflection would go
  // below the surface. The corrected normal is unit length, in the plane of N and Ng, and its
  // reflection rises exactly to the threshold t = min(0.9 Ng.I, 0.01).
  const Vec3 ng(0.0f, 0.0f, 1.0f);
  const Vec3 i = unit(1.0f, 0.0f, 0.2f);
  const Vec3 n = unit(-0.6f, 0.0f, 1.0f);
  ASSERT_LT(dot(reflect_about(n, i), ng), 0.0f);
  const Vec3 out = ensure_valid_reflection(ng, i, n);
  EXPECT_NEAR(length(out), 1.0f, 1e-5f);
  EXPECT_NEAR(out.y, 0.0f, 1e-6f);
  EXPECT_LT(out.x, 0.0f);  // still tilted the same way, only less
  EXPECT_GT(out.x, n.x);
  const float t = std::fmin(0.9f * dot(ng, i), 0.01f);
  EXPECT_NEAR(dot(reflect_about(out, i), ng), t, 1e-4f);
}

TEST(ValidReflection, WorksOutOfPlaneAndForAnyGeometricNormal) {
  const Vec3 ng = unit(0.2f, -0.4f, 0.9f);
  const Vec3 side = normalize(unit(0.9f, 0.5f, 0.1f) - ng * dot(unit(0.9f, 0.5f, 0.1f), ng));
  const Vec3 i = normalize(side + ng * 0.15f);
  const Vec3 n = normalize(ng - side * 0.8f + cross(ng, side) * 0.1f);
  ASSERT_LT(dot(reflect_about(n, i), ng), 0.0f);
  const Vec3 out = ensure_valid_reflection(ng, i, n);
  EXPECT_NEAR(length(out), 1.0f, 1e-5f);
  EXPECT_NEAR(dot(out, normalize(cross(n, ng))), 0.0f, 1e-5f);  // in the plane of N and Ng
  const float t = std::fmin(0.9f * dot(ng, i), 0.01f);
  EXPECT_NEAR(dot(reflect_about(out, i), ng), t, 1e-4f);
}

}  // namespace
}  // namespace valid_reflection_test
}  // namespace photon

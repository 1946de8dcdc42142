#include "photon/integrators/photon_map/irradiance_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace photon {
namespace irradiance_cache_test {
namespace {

IrradianceRecord record(Vec3 p, Vec3 n, Vec3 value, float radius) {
  IrradianceRecord r;
  r.p = p;
  r.n = normalize(n);
  r.value = value;
  r.radius = radius;
  return r;
}

TEST(IrradianceCache, WardErrorAddsDistanceOverRadiusAndNormalTerm) {
  const IrradianceRecord r = record({0, 0, 0}, {0, 0, 1}, Vec3(1.0f), 2.0f);
  EXPECT_FLOAT_EQ(ward_error(r, {0, 0, 0}, {0, 0, 1}), 0.0f);
  EXPECT_FLOAT_EQ(ward_error(r, {1, 0, 0}, {0, 0, 1}), 0.5f);
  // Normal tilted by 60 degrees: sqrt(1 - cos 60) = sqrt(0.5).
  const Vec3 tilted(std::sin(kPi / 3), 0.0f, std::cos(kPi / 3));
  EXPECT_NEAR(ward_error(r, {0, 1, 0}, tilted), 0.5f + std::sqrt(0.5f), 1e-6f);
  EXPECT_TRUE(std::isinf(ward_error(r, {0, 0, 0}, {0, 0, -1})));
}

TEST(IrradianceCache, AcceptsOnlyRecordsWithErrorBelowAccuracy) {
  const float a = 0.25f;
  const IrradianceCache cache({record({0, 0, 0}, {0, 0, 1}, Vec3(2.0f), 1.0f)}, a);
  Vec3 v;
  // eps = 0.2 < a: accepted, and the only record gives its value.
  ASSERT_TRUE(cache.lookup({0.2f, 0, 0}, {0, 0, 1}, &v));
  EXPECT_FLOAT_EQ(v.x, 2.0f);
  EXPECT_TRUE(cache.covers({0.2f, 0, 0}, {0, 0, 1}, a));
  EXPECT_FALSE(cache.covers({0.2f, 0, 0}, {0, 0, 1}, 0.5f * a));  // stricter build test
  // eps = 0.3 > a: rejected (w = 1/eps < 1/a).
  EXPECT_FALSE(cache.lookup({0.3f, 0, 0}, {0, 0, 1}, &v));
  EXPECT_FALSE(cache.covers({0.3f, 0, 0}, {0, 0, 1}, a));
  // Same place, normal tilted so that sqrt(1 - n.ni) = 0.3 > a: rejected.
  const float c = 1.0f - 0.09f;
  EXPECT_FALSE(cache.lookup({0, 0, 0}, {std::sqrt(1 - c * c), 0, c}, &v));
  // A record 0.1 above the surface is in front of the point (Ward's d_i < 0): rejected,
  // although eps = 0.1 < a.
  const IrradianceCache above({record({0, 0, 0.1f}, {0, 0, 1}, Vec3(2.0f), 1.0f)}, a);
  EXPECT_FALSE(above.lookup({0, 0, 0}, {0, 0, 1}, &v));
  // Below the point it is behind: accepted.
  EXPECT_TRUE(above.lookup({0, 0, 0.2f}, {0, 0, 1}, &v));
}

TEST(IrradianceCache, InterpolationWeightsFallToZeroAtTheDomainEdge) {
  const float a = 0.5f;
  const IrradianceCache cache({record({0, 0, 0}, {0, 0, 1}, Vec3(1.0f), 1.0f),
                               record({0.6f, 0, 0}, {0, 0, 1}, Vec3(3.0f), 1.0f)},
                              a);
  Vec3 v;
  // Halfway: equal weights.
  ASSERT_TRUE(cache.lookup({0.3f, 0, 0}, {0, 0, 1}, &v));
  EXPECT_NEAR(v.x, 2.0f, 1e-5f);
  // Weights w_i = 1/eps_i - 1/a: at x = 0.15, eps = 0.15 and 0.45.
  ASSERT_TRUE(cache.lookup({0.15f, 0, 0}, {0, 0, 1}, &v));
  const float w0 = 1 / 0.15f - 2, w1 = 1 / 0.45f - 2;
  EXPECT_NEAR(v.x, (w0 * 1 + w1 * 3) / (w0 + w1), 1e-4f);
  // Just inside the second record's domain edge, it has almost no say: continuous.
  ASSERT_TRUE(cache.lookup({0.1001f, 0, 0}, {0, 0, 1}, &v));
  EXPECT_NEAR(v.x, 1.0f, 1e-3f);
  ASSERT_TRUE(cache.lookup({0.0999f, 0, 0}, {0, 0, 1}, &v));
  EXPECT_FLOAT_EQ(v.x, 1.0f);
}

// The tree must find exactly the records a brute-force scan finds.
TEST(IrradianceCache, LookupMatchesBruteForceOverManyRecords) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<IrradianceRecord> records;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 n = u(rng) < 0.5f ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    records.push_back(record({u(rng) * 4, u(rng) * 4, u(rng) * 0.01f}, n, Vec3(u(rng), u(rng), 1),
                             0.05f + u(rng) * u(rng) * 2.0f));
  }
  const float a = 0.3f;
  const IrradianceCache cache(records, a);
  ASSERT_EQ(cache.size(), records.size());
  int found = 0;
  for (int q = 0; q < 2000; ++q) {
    const Vec3 p(u(rng) * 4, u(rng) * 4, 0.005f);
    const Vec3 n = u(rng) < 0.5f ? Vec3(0, 0, 1) : normalize(Vec3(0.1f, 0, 1));
    double sum = 0.0, weights = 0.0;
    for (const IrradianceRecord& r : records) {
      const float eps = ward_error(r, p, n);
      if (eps < a && !record_in_front(r, p, n)) {
        const double w = 1.0 / std::max(eps, 1e-4f * a) - 1.0 / a;
        sum += w * r.value.x;
        weights += w;
      }
    }
    Vec3 v;
    const bool hit = cache.lookup(p, n, &v);
    ASSERT_EQ(hit, weights > 0.0) << q;
    if (hit) {
      ++found;
      EXPECT_NEAR(v.x, sum / weights, 1e-4) << q;
    }
  }
  EXPECT_GT(found, 500);  // the comparison covers accepted lookups, not only misses
}

TEST(IrradianceCache, DropsInvalidRecordsAndHandlesEmpty) {
  const IrradianceCache empty;
  Vec3 v;
  EXPECT_FALSE(empty.lookup({0, 0, 0}, {0, 0, 1}, &v));
  EXPECT_FALSE(empty.covers({0, 0, 0}, {0, 0, 1}, 1.0f));
  const IrradianceCache cache({record({0, 0, 0}, {0, 0, 1}, Vec3(NAN), 1.0f),
                               record({0, 0, 0}, {0, 0, 1}, Vec3(1.0f), 0.0f),
                               record({0, 0, 0}, {0, 0, 1}, Vec3(1.0f), INFINITY)},
                              0.25f);
  EXPECT_TRUE(cache.empty());
}

}  // namespace
}  // namespace irradiance_cache_test
}  // namespace photon

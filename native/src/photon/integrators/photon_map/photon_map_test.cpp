#include "photon/integrators/photon_map/photon_map.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "photon/base/rng.h"

namespace photon {
namespace photon_map_test {
namespace {

std::vector<Photon> random_photons(size_t n, uint64_t seed) {
  std::vector<Photon> photons;
  for (size_t i = 0; i < n; ++i) {
    const uint64_t h = mix64(seed * 1000003 + i);
    const Vec3 p(to_unit_float(h), to_unit_float(h << 20), to_unit_float(mix64(h)));
    const uint8_t flags = static_cast<uint8_t>(1u << (mix64(h + 1) % 3));
    photons.push_back(Photon::make(p, Vec3(0, 0, -1), Vec3(1.0f), flags, Vec3(0, 0, 1)));
  }
  return photons;
}

TEST(Rgbe, RoundTripsWithinHalfAStepOfTheLargestChannel) {
  for (const Vec3 c : {Vec3(1.0f, 0.5f, 0.25f), Vec3(3e-7f, 1e-7f, 2e-7f),
                       Vec3(1234.5f, 0.0f, 7.0f), Vec3(0.999f, 0.999f, 0.999f)}) {
    uint8_t e[4];
    encode_rgbe(c, e);
    const Vec3 d = decode_rgbe(e);
    const float step = max_component(c) / 128.0f;  // the mantissa keeps >= 7 significant bits
    EXPECT_NEAR(d.x, c.x, step);
    EXPECT_NEAR(d.y, c.y, step);
    EXPECT_NEAR(d.z, c.z, step);
  }
  uint8_t e[4];
  encode_rgbe(Vec3(0.0f), e);
  EXPECT_EQ(decode_rgbe(e).x, 0.0f);
  encode_rgbe(Vec3(NAN, 1.0f, 1.0f), e);
  EXPECT_TRUE(is_finite(decode_rgbe(e)));
}

TEST(Rgbe, RoundingIsUnbiasedOverManyPowers) {
  // Truncating encoders lose ~0.2% of the flux on average; rounding keeps the sum.
  double sum_in = 0.0, sum_out = 0.0;
  for (int i = 0; i < 10000; ++i) {
    const float v = 0.1f + to_unit_float(mix64(i));
    uint8_t e[4];
    encode_rgbe(Vec3(v), e);
    sum_in += v;
    sum_out += decode_rgbe(e).x;
  }
  EXPECT_NEAR(sum_out / sum_in, 1.0, 2e-4);
}

TEST(Photon, DirectionIsQuantisedToAboutOneDegree) {
  for (int i = 0; i < 100; ++i) {
    const uint64_t h = mix64(i);
    const Vec3 d = normalize(Vec3(to_unit_float(h) - 0.5f, to_unit_float(h << 20) - 0.5f,
                                  to_unit_float(mix64(h)) - 0.5f));
    const Photon ph = Photon::make(Vec3(0.0f), d, Vec3(1.0f), kPhotonDirect, -d);
    EXPECT_GT(dot(ph.direction(), d), std::cos(0.03f)) << i;
  }
}

TEST(PhotonMap, KNearestMatchesBruteForce) {
  const auto photons = random_photons(20000, 3);
  const PhotonMap map(photons);
  ASSERT_EQ(map.size(), photons.size());
  std::vector<PhotonNeighbor> found;
  for (int q = 0; q < 200; ++q) {
    const uint64_t h = mix64(q + 99);
    const Vec3 p(to_unit_float(h), to_unit_float(h << 20), to_unit_float(mix64(h)));
    const size_t k = 1 + q % 60;
    const float radius = q % 4 == 0 ? 0.02f : 0.3f;
    const uint8_t mask = q % 3 == 0 ? kPhotonAny : kPhotonIndirect | kPhotonCaustic;
    map.k_nearest(p, k, radius, mask, &found);
    std::vector<float> expected;
    for (const Photon& ph : photons) {
      const float d2 = length_squared(ph.pos() - p);
      if ((ph.flags & mask) && d2 < radius * radius) expected.push_back(d2);
    }
    std::sort(expected.begin(), expected.end());
    expected.resize(std::min(expected.size(), k));
    std::vector<float> got;
    for (const PhotonNeighbor& nb : found) {
      got.push_back(nb.distance_squared);
      EXPECT_TRUE(map[nb.index].flags & mask);
      EXPECT_FLOAT_EQ(length_squared(map[nb.index].pos() - p), nb.distance_squared);
    }
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, expected) << "query " << q;
  }
}

TEST(PhotonMap, EmptyMapAndZeroKFindNothing) {
  const PhotonMap empty;
  std::vector<PhotonNeighbor> found{{1, 1.0f}};
  empty.k_nearest(Vec3(0.0f), 10, 1.0f, kPhotonAny, &found);
  EXPECT_TRUE(found.empty());
  EXPECT_EQ(empty.nearest(Vec3(0.0f), 1.0f, kPhotonAny), -1);
  const PhotonMap map(random_photons(100, 1));
  map.k_nearest(Vec3(0.5f), 0, 1.0f, kPhotonAny, &found);
  EXPECT_TRUE(found.empty());
}

// Photons of total flux Phi spread uniformly over a unit square: the irradiance is Phi / 1 m^2
// and a white Lambertian surface reflects L = E / pi. Photons arriving from below (the other
// side of a thin wall) must not count.
TEST(PhotonMap, RadianceEstimateOfUniformPhotonsIsIrradianceOverPi) {
  std::vector<Photon> photons;
  const int n = 200000;
  const float flux_per_photon = 2.0f / n;  // 2 W over 1 m^2
  for (int i = 0; i < n; ++i) {
    const uint64_t h = mix64(i);
    const Vec3 p(to_unit_float(h), to_unit_float(h << 24), 0.0f);
    photons.push_back(Photon::make(p, normalize(Vec3(0.3f, 0.1f, -1.0f)), Vec3(flux_per_photon),
                                   kPhotonIndirect, Vec3(0, 0, 1)));
    // The same again arriving from below: light on the other side of the wall.
    photons.push_back(Photon::make(p, Vec3(0, 0, 1), Vec3(5.0f * flux_per_photon), kPhotonIndirect,
                                   Vec3(0, 0, -1)));
  }
  const PhotonMap map(std::move(photons));
  std::vector<PhotonNeighbor> scratch;
  double sum = 0.0;
  const int queries = 400;
  for (int q = 0; q < queries; ++q) {
    const uint64_t h = mix64(q + 7);
    const Vec3 p(0.2f + 0.6f * to_unit_float(h), 0.2f + 0.6f * to_unit_float(h << 24), 0.0f);
    sum += map.radiance_estimate(p, Vec3(0, 0, 1), 200, 0.2f, kPhotonAny, &scratch).x;
  }
  // The k-nearest disc holds k photons of both sides, the cone filter is normalised: the mean
  // over many points equals E / pi up to the estimator's small density bias.
  EXPECT_NEAR(sum / queries, 2.0 / kPi, 0.03 * 2.0 / kPi);
}

}  // namespace
}  // namespace photon_map_test
}  // namespace photon

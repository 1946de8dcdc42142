// Photon-map estimates must not carry light through closed geometry: photons and precomputed
// radiance records of another surface near the query point (the inner face of an adjacent wall
// at a box's edge, a parallel surface across a gap) are left out (Jensen 2001, sec. 7.1).
#include <gtest/gtest.h>

#include <cmath>

#include "photon/base/rng.h"
#include "photon/integrators/photon_map/photon_map.h"
#include "photon/integrators/photon_map/radiance_cache.h"

namespace photon {
namespace light_leak_test {
namespace {

Vec3 random_unit(uint64_t h) {
  const float z = 2.0f * to_unit_float(h) - 1.0f;
  const float phi = 2.0f * kPi * to_unit_float(mix64(h));
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Photons spread over the square [x0, x0 + size] x [y0, y0 + size] of the plane z = z0 (or,
// with `wall`, over the plane x = z0 spanning y and z), all with `direction` and `normal`.
std::vector<Photon> square(uint64_t seed, int n, float z0, const Vec3& direction,
                           const Vec3& normal, bool wall = false, float lo = -1.0f,
                           float size = 2.0f) {
  std::vector<Photon> photons;
  for (int i = 0; i < n; ++i) {
    const uint64_t h = mix64(seed * 7919 + i);
    const float a = lo + size * to_unit_float(h), b = lo + size * to_unit_float(h << 24);
    const Vec3 p = wall ? Vec3(z0, a, b) : Vec3(a, b, z0);
    photons.push_back(Photon::make(p, direction, Vec3(1e-3f), kPhotonIndirect, normal));
  }
  return photons;
}

TEST(LightLeak, PhotonNormalRoundTripsWithinSevenDegreesAndKeepsFlagsAndSplitAxis) {
  std::vector<Photon> photons;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 n = random_unit(mix64(i + 1));
    const uint8_t flags = static_cast<uint8_t>(1u << (i % 3));
    const Photon ph = Photon::make(random_unit(mix64(i + 99)), -n, Vec3(1.0f), flags, n);
    EXPECT_GT(dot(ph.normal(), n), std::cos(7.0f * kPi / 180.0f)) << i;
    EXPECT_EQ(ph.path_flags(), flags);
    photons.push_back(ph);
  }
  for (const Vec3 n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0)})
    EXPECT_GT(dot(Photon::make(Vec3(0.0f), -n, Vec3(1.0f), kPhotonDirect, n).normal(), n), 0.999f);
  // Balancing writes the split axis into the byte that shares bits with the normal.
  std::vector<Vec3> normals;
  for (const Photon& ph : photons) normals.push_back(ph.normal());
  const PhotonMap map(photons);
  size_t matched = 0;
  for (size_t i = 0; i < map.size(); ++i) {
    EXPECT_LT(map[i].split_axis(), 3);
    for (size_t j = 0; j < photons.size(); ++j)
      if (photons[j].position[0] == map[i].position[0] &&
          photons[j].position[1] == map[i].position[1] &&
          photons[j].position[2] == map[i].position[2]) {
        EXPECT_EQ(length_squared(map[i].normal() - normals[j]), 0.0f);
        EXPECT_EQ(map[i].path_flags(), photons[j].path_flags());
        ++matched;
        break;
      }
  }
  EXPECT_EQ(matched, map.size());
}

// A closed 2 m box with light inside, seen from outside at the bottom edge of its +x wall: the
// indirect photons on the inside of its bottom face near that edge travel in every direction,
// many of them towards -x, which the incoming-direction test alone accepts for the outer face.
TEST(LightLeak, OuterFaceAtAnEdgeGetsNoPhotonsOfTheInnerFaces) {
  std::vector<Photon> photons;
  for (int i = 0; i < 20000; ++i) {
    const uint64_t h = mix64(i + 5);
    // Inside of the bottom face (z = 0, lit from above: normal +z), travelling down and -x.
    const Vec3 p(1.0f - 0.3f * to_unit_float(h), 2.0f * to_unit_float(h << 24) - 1.0f, 0.0f);
    photons.push_back(Photon::make(p, normalize(Vec3(-0.5f, 0.1f, -1.0f)), Vec3(1e-3f),
                                   kPhotonIndirect, Vec3(0, 0, 1)));
    // Inside of the +x wall (normal -x), travelling +x and down.
    const Vec3 q(1.0f, 2.0f * to_unit_float(mix64(h)) - 1.0f, 0.3f * to_unit_float(h << 40));
    photons.push_back(Photon::make(q, normalize(Vec3(1.0f, 0.0f, -0.4f)), Vec3(1e-3f),
                                   kPhotonIndirect, Vec3(-1, 0, 0)));
  }
  const PhotonMap map(std::move(photons));
  std::vector<PhotonNeighbor> scratch;
  // Outer face of the +x wall (normal +x) just above the bottom edge; outer bottom face (-z).
  for (const float z : {0.005f, 0.02f, 0.05f}) {
    const Vec3 outside =
        map.radiance_estimate(Vec3(1.0f, 0.0f, z), Vec3(1, 0, 0), 50, 0.5f, kPhotonAny, &scratch);
    EXPECT_EQ(max_component(outside), 0.0f) << z;
  }
  EXPECT_EQ(max_component(map.radiance_estimate(Vec3(0.99f, 0.0f, 0.0f), Vec3(0, 0, -1), 50, 0.5f,
                                                kPhotonAny, &scratch)),
            0.0f);
  // The inside of the bottom face still sees its photons.
  EXPECT_GT(max_component(map.radiance_estimate(Vec3(0.85f, 0.0f, 0.0f), Vec3(0, 0, 1), 50, 0.5f,
                                                kPhotonAny, &scratch)),
            0.0f);
}

// The floor 0.5 m under a closed box lit inside: the photons on the inside of the box's bottom
// face lie over the floor, face the same way (+z) and travel down, as the floor's own would.
TEST(LightLeak, ParallelSurfaceAcrossAGapGivesNoPhotons) {
  const PhotonMap map(square(1, 20000, 0.5f, normalize(Vec3(0.2f, 0.1f, -1.0f)), Vec3(0, 0, 1)));
  std::vector<PhotonNeighbor> scratch;
  for (const Vec3 p : {Vec3(0.0f, 0.0f, 0.0f), Vec3(1.2f, 0.0f, 0.0f), Vec3(0.9f, 0.9f, 0.0f)})
    EXPECT_EQ(
        max_component(map.radiance_estimate(p, Vec3(0, 0, 1), 100, 1.5f, kPhotonAny, &scratch)),
        0.0f)
        << p.x << " " << p.y;
  // On the plane itself the estimate is the photons' irradiance over pi: 20 W over 4 m^2.
  double sum = 0.0;
  for (int q = 0; q < 100; ++q) {
    const uint64_t h = mix64(q + 3);
    const Vec3 p(0.6f * to_unit_float(h) - 0.3f, 0.6f * to_unit_float(h << 24) - 0.3f, 0.5f);
    sum += map.radiance_estimate(p, Vec3(0, 0, 1), 100, 1.5f, kPhotonAny, &scratch).x;
  }
  EXPECT_NEAR(sum / 100, 5.0 / kPi, 0.04 * 5.0 / kPi);
}

// A face lit on both sides: densely inside a closed box (a lamp), sparsely outside (a world
// seen through the gap under the box). The radiance precomputed at an outside photon's own
// position counts that photon; the disc must be that of the outside photons, not one shrunk
// by the inside photons at the same place, which would count it over a tiny area (this lit the
// floor under a sealed lamp's box 25% brighter than without the lamp).
TEST(LightLeak, EstimateAtAPhotonOfTheDimSideKeepsToItsOwnSide) {
  std::vector<Photon> photons =
      square(2, 40000, 0.5f, normalize(Vec3(0.1f, 0.2f, -1.0f)), Vec3(0, 0, 1));  // inside
  const std::vector<Photon> outside =
      square(3, 2000, 0.5f, normalize(Vec3(-0.2f, 0.1f, 1.0f)), Vec3(0, 0, -1));
  photons.insert(photons.end(), outside.begin(), outside.end());
  const PhotonMap map(photons);
  // The outside's 2 W over 4 m^2: radiance 0.5 / pi for albedo 1.
  const double expected = 0.5 / kPi;
  std::vector<PhotonNeighbor> scratch;
  double at_photon = 0.0, plain = 0.0;
  int n = 0;
  for (size_t i = 0; i < outside.size(); i += 20) {
    const Vec3 p = outside[i].pos();
    if (std::fabs(p.x) > 0.7f || std::fabs(p.y) > 0.7f) continue;  // away from the edges
    at_photon += map.radiance_estimate(p, Vec3(0, 0, -1), 50, 1.5f, kPhotonAny, &scratch, true).x;
    plain += map.radiance_estimate(p, Vec3(0, 0, -1), 50, 1.5f, kPhotonAny, &scratch).x;
    ++n;
  }
  ASSERT_GT(n, 20);
  EXPECT_NEAR(at_photon / n, expected, 0.08 * expected);
  // What the disc of all photons made of it (2.2 times the radiance here): the photon itself
  // and its few outside neighbours over a disc sized for 21 times as many photons.
  EXPECT_GT(plain / n, 1.5 * expected);
}

// A gently curved surface keeps its photons: a sphere of radius 2 m, queried with a 0.3 m disc.
TEST(LightLeak, CurvedSurfaceKeepsItsPhotons) {
  std::vector<Photon> photons;
  const float radius = 2.0f;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const Vec3 normal = random_unit(mix64(i + 11));
    photons.push_back(Photon::make(normal * radius, -normal, Vec3(1e-3f), kPhotonIndirect, normal));
  }
  const PhotonMap map(std::move(photons));
  std::vector<PhotonNeighbor> scratch;
  // 100 W over 4 pi r^2; radiance E / pi.
  const double expected = n * 1e-3 / (4.0 * kPi * radius * radius) / kPi;
  double sum = 0.0;
  for (int q = 0; q < 50; ++q) {
    const Vec3 normal = random_unit(mix64(q + 1000));
    sum += map.radiance_estimate(normal * radius, normal, 400, 0.6f, kPhotonAny, &scratch).x;
  }
  EXPECT_NEAR(sum / 50, expected, 0.05 * expected);
}

TEST(LightLeak, RadianceRecordOfAParallelSurfaceAcrossAGapIsNotUsed) {
  // The floor's record 0.5 m under the inside of a box's bottom face; both face +z.
  std::vector<RadianceRecord> records(2);
  records[0].p = Vec3(0.0f, 0.0f, 0.0f);
  records[0].n = Vec3(0, 0, 1);
  records[0].radiance = Vec3(1.0f);
  records[1].p = Vec3(3.0f, 0.0f, 0.0f);  // far away, same plane
  records[1].n = Vec3(0, 0, 1);
  records[1].radiance = Vec3(2.0f);
  const RadianceCache cache(records, 1.0f);
  EXPECT_EQ(cache.nearest(Vec3(0.1f, 0.0f, 0.5f), Vec3(0, 0, 1), 0.5f), nullptr);
  // On the floor's own plane the record is found.
  const RadianceRecord* same_plane = cache.nearest(Vec3(0.3f, 0.2f, 0.0f), Vec3(0, 0, 1), 0.5f);
  ASSERT_NE(same_plane, nullptr);
  EXPECT_EQ(same_plane->radiance.x, 1.0f);
}

}  // namespace
}  // namespace light_leak_test
}  // namespace photon

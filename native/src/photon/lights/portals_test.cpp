// Portals as sampling techniques (portals.h): which points they face, a density that
// integrates to one and that the samples follow, and lines through them for photons.
#include "photon/lights/portals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "photon/base/rng.h"
#include "photon/base/sampling.h"

namespace photon {
namespace portals_test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Two windows in the wall x = 1 of a room, their light going along -x into it: a rectangle
// 0.8 wide and 0.6 tall, and an ellipse beside it.
std::vector<Portal> two_windows() {
  Portal rect;
  rect.center = Vec3(1.0f, -0.5f, 0.5f);
  rect.half_x = Vec3(0.0f, 0.4f, 0.0f);
  rect.half_y = Vec3(0.0f, 0.0f, 0.3f);
  rect.direction = Vec3(-1.0f, 0.0f, 0.0f);
  Portal round = rect;
  round.center = Vec3(1.0f, 0.6f, 0.4f);
  round.shape = AreaShape::kEllipse;
  round.half_x = Vec3(0.0f, 0.3f, 0.0f);
  round.half_y = Vec3(0.0f, 0.0f, 0.2f);
  return {rect, round};
}

TEST(Portals, FaceThePointsTheirLightGoesTo) {
  const PortalSet set(two_windows());
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set.facing(Vec3(0.0f)), 2u);
  EXPECT_EQ(set.facing(Vec3(2.0f, 0.0f, 0.0f)), 0u);  // outside the house
  Vec3 wi;
  float pdf;
  EXPECT_FALSE(set.sample(Vec3(2.0f, 0.0f, 0.0f), 0.3f, Vec2(0.5f, 0.5f), &wi, &pdf));
  EXPECT_EQ(set.pdf(Vec3(2.0f, 0.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)), 0.0f);
}

TEST(Portals, DegenerateOnesAreLeftOut) {
  std::vector<Portal> portals = two_windows();
  Portal flat;
  flat.half_y = Vec3(0.0f);
  Portal broken;
  broken.center = Vec3(NAN, 0.0f, 0.0f);
  portals.push_back(flat);
  portals.push_back(broken);
  size_t skipped = 0;
  const PortalSet set(portals, &skipped);
  EXPECT_EQ(set.size(), 2u);
  EXPECT_EQ(skipped, 2u);
}

TEST(Portals, DensityIntegratesToOneOverTheSphere) {
  const PortalSet set(two_windows());
  for (const Vec3& p : {Vec3(0.0f), Vec3(0.8f, 0.0f, 0.2f), Vec3(-2.0f, 1.0f, 1.5f)}) {
    const int n = 2000000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      Sampler sampler(2, 0, static_cast<uint32_t>(i), n);
      sum += set.pdf(p, sample_uniform_sphere(sampler.get_2d()));
    }
    EXPECT_NEAR(sum / n * 4.0 * kPiD, 1.0, 0.01) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(Portals, SamplesGoThroughAFacingPortalWithTheDensityTheyReport) {
  // The integral of max(cos, 0) to the ceiling over the directions through the windows, by
  // the samples (the mean of cos / pdf) and by uniform directions that pass through them.
  const PortalSet set(two_windows());
  const Vec3 p(-0.5f, 0.1f, 0.0f);
  const int n = 400000;
  double by_samples = 0.0, by_uniform = 0.0;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(3, 0, static_cast<uint32_t>(i), n);
    Vec3 wi;
    float pdf;
    ASSERT_TRUE(set.sample(p, sampler.get_1d(), sampler.get_2d(), &wi, &pdf));
    ASSERT_NEAR(pdf, set.pdf(p, wi), 1e-5f * pdf);
    ASSERT_GT(wi.x, 0.0f);  // towards the wall
    by_samples += std::max(wi.z, 0.0f) / pdf;
    const Vec3 w = sample_uniform_sphere(sampler.get_2d());
    // Directions through the windows, counted once each (the density is positive there).
    if (set.pdf(p, w) > 0.0f) by_uniform += std::max(w.z, 0.0f) * 4.0 * kPiD;
  }
  EXPECT_NEAR(by_samples / n, by_uniform / n, 0.02 * by_uniform / n);
}

TEST(Portals, LinesCrossThePortalTheyWereDrawnOnIntoTheRoom) {
  const PortalSet set(two_windows());
  EXPECT_NEAR(set.total_area(), 0.8f * 0.6f + kPi * 0.3f * 0.2f, 1e-6f);
  const int n = 100000;
  int on_ellipse = 0;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(4, 0, static_cast<uint32_t>(i), n);
    Vec3 point, d;
    set.sample_line(sampler.get_1d(), sampler.get_2d(), sampler.get_2d(), &point, &d);
    ASSERT_NEAR(point.x, 1.0f, 1e-6f);
    ASSERT_LT(d.x, 0.0f);  // into the room
    ASSERT_NEAR(length(d), 1.0f, 1e-5f);
    EXPECT_GE(set.crossings(point - d * 0.5f, d), 1);
    on_ellipse += point.y > 0.2f ? 1 : 0;
  }
  // Portals are picked by area.
  EXPECT_NEAR(static_cast<double>(on_ellipse) / n, kPi * 0.06 / (0.48 + kPi * 0.06), 0.005);
  // A line going out of the room crosses none (light through a portal goes in).
  EXPECT_EQ(set.crossings(Vec3(0.0f, -0.5f, 0.5f), Vec3(1.0f, 0.0f, 0.0f)), 0);
  EXPECT_EQ(set.crossings(Vec3(0.0f, -0.5f, 0.5f), Vec3(-1.0f, 0.0f, 0.0f)), 1);
}

}  // namespace
}  // namespace portals_test
}  // namespace photon
